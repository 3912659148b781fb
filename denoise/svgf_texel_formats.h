// Descriptor formats of the SVGF passes whose read-only planes are uniform texel buffers
// (shaders/common/access.glsl); VK_FORMAT_UNDEFINED = std430 storage buffer. Shared by the SVGF
// and two-history hosts, which run the same svgf_filter_moments / svgf_atrous shaders.
#pragma once

#include <array>

#include <vulkan/vulkan.h>

#include "denoise/params.h"
#include "shaders/shared_constants.h"

namespace fovrt {

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
    std::array<VkFormat, SVGF_GUIDE_BINDINGS> f{};
    f.fill(VK_FORMAT_UNDEFINED);
    f[SVGF_GUIDE_B_DEPTH] = VK_FORMAT_R32_SFLOAT;
    f[SVGF_GUIDE_B_NORMAL] = VK_FORMAT_R32G32B32_SFLOAT;
    f[SVGF_GUIDE_B_OBJECT] = VK_FORMAT_R32_UINT;
    return f;
}

inline std::array<VkFormat, SVGF_MODULATE_BINDINGS> SvgfModulateTexelFormats() {
    std::array<VkFormat, SVGF_MODULATE_BINDINGS> f{};
    f.fill(VK_FORMAT_UNDEFINED);
    f[SVGF_MODULATE_B_ILLUM0] = VK_FORMAT_R32G32B32A32_SFLOAT;
    f[SVGF_MODULATE_B_ILLUM1] = VK_FORMAT_R32G32B32A32_SFLOAT;
    f[SVGF_MODULATE_B_ALBEDO] = VK_FORMAT_R32G32B32_SFLOAT;
    f[SVGF_MODULATE_B_EMISSION] = VK_FORMAT_R32G32B32_SFLOAT;
    return f;
}

inline std::array<VkFormat, SVGF_CLASSIFY_BINDINGS> SvgfClassifyTexelFormats(Precision precision) {
    std::array<VkFormat, SVGF_CLASSIFY_BINDINGS> f{};
    f.fill(VK_FORMAT_UNDEFINED);
    f[SVGF_CLASSIFY_B_GUIDE] = VK_FORMAT_R32G32B32A32_SFLOAT;
    f[SVGF_CLASSIFY_B_LENGTH] = precision == Precision::Fp16 ? VK_FORMAT_R16_SFLOAT : VK_FORMAT_R32_SFLOAT;
    return f;
}

inline std::array<VkFormat, SVGF_MOMENTS_BINDINGS> SvgfMomentsTexelFormats(Precision precision) {
    const bool half = precision == Precision::Fp16;
    std::array<VkFormat, SVGF_MOMENTS_BINDINGS> f{};
    f.fill(VK_FORMAT_UNDEFINED);
    f[SVGF_MOMENTS_B_ILLUM_IN] = VK_FORMAT_R32G32B32A32_SFLOAT;
    f[SVGF_MOMENTS_B_GUIDE] = VK_FORMAT_R32G32B32A32_SFLOAT;
    f[SVGF_MOMENTS_B_DEPTH_GRAD] = VK_FORMAT_R32G32_SFLOAT;
    f[SVGF_MOMENTS_B_MOMENTS] = half ? VK_FORMAT_R16G16_SFLOAT : VK_FORMAT_R32G32_SFLOAT;
    f[SVGF_MOMENTS_B_LENGTH] = half ? VK_FORMAT_R16_SFLOAT : VK_FORMAT_R32_SFLOAT;
    return f;
}

// Formats of "svgf_atrous_pair"; the one-channel "svgf_atrous" uses the first SVGF_ATROUS_BINDINGS.
inline std::array<VkFormat, SVGF_ATROUS_PAIR_BINDINGS> SvgfAtrousTexelFormats() {
    std::array<VkFormat, SVGF_ATROUS_PAIR_BINDINGS> f{};
    f.fill(VK_FORMAT_UNDEFINED);
    f[SVGF_ATROUS_B_ILLUM_IN] = VK_FORMAT_R32G32B32A32_SFLOAT;
    f[SVGF_ATROUS_B_ILLUM_IN2] = VK_FORMAT_R32G32B32A32_SFLOAT;
    f[SVGF_ATROUS_B_GUIDE] = VK_FORMAT_R32G32B32A32_SFLOAT;
    f[SVGF_ATROUS_B_DEPTH_GRAD] = VK_FORMAT_R32G32_SFLOAT;
    return f;
}

}  // namespace fovrt
