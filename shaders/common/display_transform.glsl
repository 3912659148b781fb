// The display transform, written once for GLSL and C++: the same text compiles as both (C++ sees
// it in namespace fovrt::glsl, with std::pow and std::min brought in). Every 8-bit image fovrt
// shows or writes goes through it: PNG output (src/io/png.cpp), the LDR metrics' ToneMap
// (src/metrics/tonemap.h) and the live preview's display pass (shaders/display_compose.comp and
// its C++ reference, src/display/display_compose.cpp).
//
//   linear  = hdr · scale            scale = 2^exposure (stops; output.exposure), 1 for display data
//   linear  = 0 when not finite or negative
//   mapped  = min(linear, 1)         (clamp, the default)   or   linear / (1 + linear)   (Reinhard)
//   encoded = sRGB OETF (IEC 61966-2-1) of mapped
//   byte    = ⌊encoded · 255 + 0.5⌋  (round half up)
//
// The host computes scale = exp2(exposure) once and hands the float to the shader, so both sides
// multiply by the same number; what still differs between them is pow and division, whose GPU
// precision is a few ULP: at most 1 LSB in the byte.
#ifndef FOVRT_DISPLAY_TRANSFORM_GLSL
#define FOVRT_DISPLAY_TRANSFORM_GLSL

#ifdef __cplusplus
#include <algorithm>
#include <cmath>
#include <cstdint>
namespace fovrt::glsl {
using std::min;
using std::pow;
using uint = uint32_t;
#define FOVRT_SHARED_FN inline
#define FOVRT_IS_FINITE(v) std::isfinite(v)
#else
#define FOVRT_SHARED_FN
#define FOVRT_IS_FINITE(v) (!isnan(v) && !isinf(v))
#endif

// sRGB OETF, linear [0,1] → encoded [0,1].
FOVRT_SHARED_FN float fovrt_srgb_encode(float linear) {
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * pow(linear, 1.0f / 2.4f) - 0.055f;
}

// Exposure, sanitising and the tone curve: HDR value → displayable linear [0,1].
FOVRT_SHARED_FN float fovrt_display_linear(float hdr, float scale, bool reinhard) {
    float v = hdr * scale;
    if (!FOVRT_IS_FINITE(v) || v < 0.0f) v = 0.0f;
    return reinhard ? v / (1.0f + v) : min(v, 1.0f);
}

// Encoded [0,1] → 8-bit code value.
FOVRT_SHARED_FN uint fovrt_display_quantize(float encoded) { return uint(encoded * 255.0f + 0.5f); }

// The whole transform of one channel.
FOVRT_SHARED_FN uint fovrt_display_byte(float hdr, float scale, bool reinhard) {
    return fovrt_display_quantize(fovrt_srgb_encode(fovrt_display_linear(hdr, scale, reinhard)));
}

#undef FOVRT_SHARED_FN
#undef FOVRT_IS_FINITE
#ifdef __cplusplus
}  // namespace fovrt::glsl
#endif

#endif
