// Descriptor formats of the SVGF passes whose read-only planes are uniform texel buffers
// (shaders/common/access.glsl); VK_FORMAT_UNDEFINED = std430 storage buffer. Shared by the SVGF
// and two-history hosts, which run the same svgf_filter_moments / svgf_atrous shaders.
#pragma once

#include <array>
#include <initializer_list>
#include <utility>

#include <vulkan/vulkan.h>

#include "denoise/params.h"
#include "shaders/common/two_history_constants.glsl"
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


// The descriptor format of each binding of a list (shaders/bindings.h) by its kind: texel
// buffers their FORMAT (history planes their 16-bit twin in fp16; HTEXEL3 planes are storage in
// fp16), storage buffers VK_FORMAT_UNDEFINED.
#define FOVRT_VK_FORMAT_R32F VK_FORMAT_R32_SFLOAT
#define FOVRT_VK_FORMAT_RG32F VK_FORMAT_R32G32_SFLOAT
#define FOVRT_VK_FORMAT_RGB32F VK_FORMAT_R32G32B32_SFLOAT
#define FOVRT_VK_FORMAT_RGBA32F VK_FORMAT_R32G32B32A32_SFLOAT
#define FOVRT_VK_FORMAT_R32UI VK_FORMAT_R32_UINT
#define FOVRT_TEXEL_FORMAT_TEXEL(format) FOVRT_VK_FORMAT_##format
#define FOVRT_TEXEL_FORMAT_UTEXEL(format) FOVRT_VK_FORMAT_##format
#define FOVRT_TEXEL_FORMAT_HTEXEL(format) HistoryTexelFormat(FOVRT_VK_FORMAT_##format, precision)
#define FOVRT_TEXEL_FORMAT_HTEXEL3(format) \
    (precision == Precision::Fp16 ? VK_FORMAT_UNDEFINED : FOVRT_VK_FORMAT_##format)
#define FOVRT_TEXEL_FORMAT_READ(type) VK_FORMAT_UNDEFINED
#define FOVRT_TEXEL_FORMAT_WRITE(type) VK_FORMAT_UNDEFINED
#define FOVRT_TEXEL_FORMAT_RW(type) VK_FORMAT_UNDEFINED
#define FOVRT_TEXEL_FORMAT_LIST(type) VK_FORMAT_UNDEFINED
#define FOVRT_TEXEL_FORMAT_ROW(pass, name, slot, kind, format, variable) \
    formats.at(size_t(slot)) = FOVRT_TEXEL_FORMAT_##kind(format);
// The texel-format table of a binding list at a precision: std::array<VkFormat, count>.
#define FOVRT_TEXEL_FORMATS(LIST, PRECISION)                               \
    [](Precision precision) {                                              \
        std::array<VkFormat, size_t(FOVRT_BINDING_COUNT(LIST))> formats{}; \
        LIST(FOVRT_TEXEL_FORMAT_ROW)                                       \
        (void)precision; /* lists without history planes ignore it */      \
        return formats;                                                    \
    }(PRECISION)

// Formats of "svgf_reproject_pair"; the one-channel "svgf_reproject" uses the first SVGF_REPROJECT_BINDINGS.
inline std::array<VkFormat, SVGF_REPROJECT_PAIR_BINDINGS> SvgfReprojectTexelFormats(Precision precision) {
    return FOVRT_TEXEL_FORMATS(SVGF_REPROJECT_PAIR_ALL_BINDING_LIST, precision);
}

inline std::array<VkFormat, SVGF_GUIDE_BINDINGS> SvgfGuideTexelFormats() {
    return FOVRT_TEXEL_FORMATS(SVGF_GUIDE_BINDING_LIST, Precision::Fp32);
}

inline std::array<VkFormat, SVGF_MODULATE_BINDINGS> SvgfModulateTexelFormats() {
    return FOVRT_TEXEL_FORMATS(SVGF_MODULATE_BINDING_LIST, Precision::Fp32);
}

inline std::array<VkFormat, SVGF_CLASSIFY_BINDINGS> SvgfClassifyTexelFormats(Precision precision) {
    return FOVRT_TEXEL_FORMATS(SVGF_CLASSIFY_BINDING_LIST, precision);
}

inline std::array<VkFormat, SVGF_MOMENTS_BINDINGS> SvgfMomentsTexelFormats(Precision precision) {
    return FOVRT_TEXEL_FORMATS(SVGF_MOMENTS_BINDING_LIST, precision);
}

// Formats of "svgf_atrous_pair"; the one-channel "svgf_atrous" uses the first SVGF_ATROUS_BINDINGS.
inline std::array<VkFormat, SVGF_ATROUS_PAIR_BINDINGS> SvgfAtrousTexelFormats() {
    return FOVRT_TEXEL_FORMATS(SVGF_ATROUS_PAIR_ALL_BINDING_LIST, Precision::Fp32);
}

// The texel-format tables of the two-history and A-SVGF passes, from their binding lists.
inline std::array<VkFormat, ASVGF_GATHER_BINDINGS> GradientGatherTexelFormats() {
    return FOVRT_TEXEL_FORMATS(ASVGF_GATHER_BINDING_LIST, Precision::Fp32);
}
inline std::array<VkFormat, ASVGF_SIGMA_BINDINGS> StratumSigmaTexelFormats() {
    return FOVRT_TEXEL_FORMATS(ASVGF_SIGMA_BINDING_LIST, Precision::Fp32);
}
inline std::array<VkFormat, ASVGF_ATROUS_BINDINGS> GradientAtrousTexelFormats() {
    return FOVRT_TEXEL_FORMATS(ASVGF_ATROUS_BINDING_LIST, Precision::Fp32);
}
inline std::array<VkFormat, TH_BLEND_BINDINGS> BlendTexelFormats(Precision precision) {
    return FOVRT_TEXEL_FORMATS(TH_BLEND_BINDING_LIST, precision);
}
inline std::array<VkFormat, ASVGF_ALPHA_BINDINGS> AlphaTexelFormats() {
    return FOVRT_TEXEL_FORMATS(ASVGF_ALPHA_BINDING_LIST, Precision::Fp32);
}
inline std::array<VkFormat, TH_GRADIENT_BINDINGS> GradientTexelFormats(Precision precision) {
    return FOVRT_TEXEL_FORMATS(TH_GRADIENT_BINDING_LIST, precision);
}

// Formats of "two_history_reproject_pair"; the one-channel shader uses the first TH_REPROJECT_BINDINGS.
inline std::array<VkFormat, TH_REPROJECT_PAIR_BINDINGS> TwoHistoryReprojectTexelFormats(Precision precision) {
    return FOVRT_TEXEL_FORMATS(TH_REPROJECT_PAIR_ALL_BINDING_LIST, precision);
}

}  // namespace fovrt
