// Descriptor formats of the SVGF passes whose read-only planes are uniform texel buffers
// (shaders/common/access.glsl); VK_FORMAT_UNDEFINED = std430 storage buffer. Shared by the SVGF
// and two-history hosts, which run the same svgf_filter_moments / svgf_atrous shaders.
#pragma once

#include <array>
#include <initializer_list>
#include <utility>

#include <vulkan/vulkan.h>

#include "denoise/params.h"
#include "shaders/shared_constants.h"

namespace fovrt {

// A table of N bindings, storage buffers except the listed (binding, texel format) pairs.
template <size_t N>
std::array<VkFormat, N> TexelFormats(std::initializer_list<std::pair<int, VkFormat>> texelBindings) {
    std::array<VkFormat, N> f{};
    f.fill(VK_FORMAT_UNDEFINED);
    for (const auto& [binding, format] : texelBindings) f.at(size_t(binding)) = format;
    return f;
}
inline constexpr VkFormat kR32 = VK_FORMAT_R32_SFLOAT, kRG32 = VK_FORMAT_R32G32_SFLOAT,
                          kRGB32 = VK_FORMAT_R32G32B32_SFLOAT, kRGBA32 = VK_FORMAT_R32G32B32A32_SFLOAT,
                          kR32U = VK_FORMAT_R32_UINT;
// A history plane's format: fp32, or its 16-bit twin in fp16 mode.
inline VkFormat HistoryTexelFormat(VkFormat fp32, Precision precision) {
    if (precision != Precision::Fp16) return fp32;
    return fp32 == kR32 ? VK_FORMAT_R16_SFLOAT : fp32 == kRG32 ? VK_FORMAT_R16G16_SFLOAT : VK_FORMAT_UNDEFINED;
}

// Formats of "svgf_reproject_pair"; the one-channel "svgf_reproject" uses the first SVGF_REPROJECT_BINDINGS.
inline std::array<VkFormat, SVGF_REPROJECT_PAIR_BINDINGS> SvgfReprojectTexelFormats(Precision precision) {
    const bool half = precision == Precision::Fp16;
    std::array<VkFormat, SVGF_REPROJECT_PAIR_BINDINGS> f{};
    f.fill(VK_FORMAT_UNDEFINED);
    f[SVGF_REPROJECT_B_COLOR_IN] = VK_FORMAT_R32G32B32_SFLOAT;
    f[SVGF_REPROJECT_B_COLOR_IN2] = VK_FORMAT_R32G32B32_SFLOAT;
    f[SVGF_REPROJECT_B_DEPTH] = VK_FORMAT_R32_SFLOAT;
    f[SVGF_REPROJECT_B_NORMAL] = VK_FORMAT_R32G32B32_SFLOAT;
    f[SVGF_REPROJECT_B_OBJECT] = VK_FORMAT_R32_UINT;
    f[SVGF_REPROJECT_B_PREV_DEPTH] = VK_FORMAT_R32_SFLOAT;
    f[SVGF_REPROJECT_B_PREV_NORMAL] = VK_FORMAT_R32G32B32_SFLOAT;
    f[SVGF_REPROJECT_B_PREV_OBJECT] = VK_FORMAT_R32_UINT;
    f[SVGF_REPROJECT_B_DEPTH_GRAD] = VK_FORMAT_R32G32_SFLOAT;
    f[SVGF_REPROJECT_B_PREV_PIXEL] = VK_FORMAT_R32G32_SFLOAT;
    // fp16 colour history stays a storage buffer (RGB16F texel buffers are rarely supported).
    f[SVGF_REPROJECT_B_PREV_COLOR] = half ? VK_FORMAT_UNDEFINED : VK_FORMAT_R32G32B32_SFLOAT;
    f[SVGF_REPROJECT_B_PREV_MOMENTS] = half ? VK_FORMAT_R16G16_SFLOAT : VK_FORMAT_R32G32_SFLOAT;
    f[SVGF_REPROJECT_B_PREV_LENGTH] = half ? VK_FORMAT_R16_SFLOAT : VK_FORMAT_R32_SFLOAT;
    f[SVGF_REPROJECT_B_PREV_WEIGHT] = half ? VK_FORMAT_R16_SFLOAT : VK_FORMAT_R32_SFLOAT;
    f[SVGF_REPROJECT_B_PREV_COLOR2] = f[SVGF_REPROJECT_B_PREV_COLOR];
    f[SVGF_REPROJECT_B_PREV_MOMENTS2] = f[SVGF_REPROJECT_B_PREV_MOMENTS];
    f[SVGF_REPROJECT_B_PREV_LENGTH2] = f[SVGF_REPROJECT_B_PREV_LENGTH];
    f[SVGF_REPROJECT_B_PREV_WEIGHT2] = f[SVGF_REPROJECT_B_PREV_WEIGHT];
    return f;
}

inline std::array<VkFormat, SVGF_GUIDE_BINDINGS> SvgfGuideTexelFormats() {
    return TexelFormats<SVGF_GUIDE_BINDINGS>(
        {{SVGF_GUIDE_B_DEPTH, kR32}, {SVGF_GUIDE_B_NORMAL, kRGB32}, {SVGF_GUIDE_B_OBJECT, kR32U}});
}

inline std::array<VkFormat, SVGF_MODULATE_BINDINGS> SvgfModulateTexelFormats() {
    return TexelFormats<SVGF_MODULATE_BINDINGS>({{SVGF_MODULATE_B_ILLUM0, kRGBA32},
                                                 {SVGF_MODULATE_B_ILLUM1, kRGBA32},
                                                 {SVGF_MODULATE_B_ALBEDO, kRGB32},
                                                 {SVGF_MODULATE_B_EMISSION, kRGB32}});
}

inline std::array<VkFormat, SVGF_CLASSIFY_BINDINGS> SvgfClassifyTexelFormats(Precision precision) {
    return TexelFormats<SVGF_CLASSIFY_BINDINGS>(
        {{SVGF_CLASSIFY_B_GUIDE, kRGBA32}, {SVGF_CLASSIFY_B_LENGTH, HistoryTexelFormat(kR32, precision)}});
}

inline std::array<VkFormat, SVGF_MOMENTS_BINDINGS> SvgfMomentsTexelFormats(Precision precision) {
    return TexelFormats<SVGF_MOMENTS_BINDINGS>({{SVGF_MOMENTS_B_ILLUM_IN, kRGBA32},
                                                {SVGF_MOMENTS_B_GUIDE, kRGBA32},
                                                {SVGF_MOMENTS_B_DEPTH_GRAD, kRG32},
                                                {SVGF_MOMENTS_B_MOMENTS, HistoryTexelFormat(kRG32, precision)},
                                                {SVGF_MOMENTS_B_LENGTH, HistoryTexelFormat(kR32, precision)}});
}

// Formats of "svgf_atrous_pair"; the one-channel "svgf_atrous" uses the first SVGF_ATROUS_BINDINGS.
inline std::array<VkFormat, SVGF_ATROUS_PAIR_BINDINGS> SvgfAtrousTexelFormats() {
    return TexelFormats<SVGF_ATROUS_PAIR_BINDINGS>({{SVGF_ATROUS_B_ILLUM_IN, kRGBA32},
                                                    {SVGF_ATROUS_B_ILLUM_IN2, kRGBA32},
                                                    {SVGF_ATROUS_B_GUIDE, kRGBA32},
                                                    {SVGF_ATROUS_B_DEPTH_GRAD, kRG32}});
}

}  // namespace fovrt
