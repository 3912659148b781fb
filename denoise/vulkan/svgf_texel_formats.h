// Descriptor formats of the planned passes, whose read-only planes are uniform texel buffers
// (shaders/common/access.glsl); VK_FORMAT_UNDEFINED = std430 storage buffer. Expanded from each
// pass's binding list (shaders/bindings.h kinds), so a format is declared once, in the list.
#pragma once

#include <array>
#include <vector>

#include <vulkan/vulkan.h>

#include "denoise/params.h"
#include "denoise/stage_shaders.h"

namespace fovrt {

// The format of a plane stored at the denoiser's precision (a history, the illumination
// ping-pong, a colour input): fp32, or its 16-bit twin in fp16 mode. RGB becomes RGBA16F (RGB16F
// texel buffers are rarely supported; the colour inputs are uploaded with a 4th half, planes.h).
inline VkFormat HistoryTexelFormat(VkFormat fp32, Precision precision) {
    if (precision != Precision::Fp16) return fp32;
    return fp32 == VK_FORMAT_R32_SFLOAT             ? VK_FORMAT_R16_SFLOAT
           : fp32 == VK_FORMAT_R32G32_SFLOAT        ? VK_FORMAT_R16G16_SFLOAT
           : fp32 == VK_FORMAT_R32G32B32_SFLOAT    ? VK_FORMAT_R16G16B16A16_SFLOAT
           : fp32 == VK_FORMAT_R32G32B32A32_SFLOAT ? VK_FORMAT_R16G16B16A16_SFLOAT
                                                    : VK_FORMAT_UNDEFINED;
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
#define FOVRT_TEXEL_FORMAT_NTEXEL(format) \
    (precision == Precision::Fp16 ? VK_FORMAT_R16G16_SINT : FOVRT_VK_FORMAT_##format)
#define FOVRT_TEXEL_FORMAT_DTEXEL(format) \
    (precision == Precision::Fp16 ? VK_FORMAT_R32_UINT : FOVRT_VK_FORMAT_##format)
#define FOVRT_TEXEL_FORMAT_OTEXEL(format) FOVRT_VK_FORMAT_##format
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

// The descriptor formats of a stage shader's one-channel or pair layout
// (denoise/stage_shaders.h), one per binding.
inline std::vector<VkFormat> StageTexelFormats(StageShader shader, bool pair, Precision precision) {
    auto vector = [](const auto& formats) { return std::vector<VkFormat>(formats.begin(), formats.end()); };
#define FOVRT_STAGE_SHADER_FORMATS(id, stem, list, pairList) \
    case StageShader::id:                                   \
        return pair ? vector(FOVRT_TEXEL_FORMATS(pairList, precision)) : vector(FOVRT_TEXEL_FORMATS(list, precision));
    switch (shader) { FOVRT_STAGE_SHADERS(FOVRT_STAGE_SHADER_FORMATS) }
#undef FOVRT_STAGE_SHADER_FORMATS
    return {};
}

}  // namespace fovrt
