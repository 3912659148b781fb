// Storage conventions: per-pixel planes are tightly packed scalar arrays indexed by
// i = y·width + x (RGB = 3 scalars, vec2 = 2). Planes stored at the denoiser's precision (the
// histories and the (illumination, variance) ping-pong) use `hfloat` / `hvec4`: float / vec4, or
// float16_t / f16vec4 (GL_EXT_shader_16bit_storage: loads/stores and conversions only) in the
// _fp16 variants.
// GLSL cannot pass buffer arrays to functions, hence macros taking the block's array.
#ifndef FOVRT_PACKING_GLSL
#define FOVRT_PACKING_GLSL

#include "../shared_constants.h"  // FOVRT_HALF_SATURATION

#ifdef FOVRT_FP16
#extension GL_EXT_shader_16bit_storage : require
#define hfloat float16_t
#define hvec4 f16vec4
#else
#define hfloat float
#define hvec4 vec4
#endif

#define LOAD2(arr, i) vec2(float((arr)[2 * (i)]), float((arr)[2 * (i) + 1]))
#define LOAD3(arr, i) vec3(float((arr)[3 * (i)]), float((arr)[3 * (i) + 1]), float((arr)[3 * (i) + 2]))
#define STORE2(arr, i, v, T) do { vec2 v_ = (v); (arr)[2 * (i)] = T(v_.x); (arr)[2 * (i) + 1] = T(v_.y); } while (false)
#define STORE3(arr, i, v, T)                                                            \
    do {                                                                                \
        vec3 v_ = (v);                                                                  \
        (arr)[3 * (i)] = T(v_.x); (arr)[3 * (i) + 1] = T(v_.y); (arr)[3 * (i) + 2] = T(v_.z); \
    } while (false)

// uint16 sample counts uploaded as raw bytes: two per uint, little-endian.
#define LOAD_U16(arr, i) (((arr)[(i) >> 1] >> (((i) & 1) * 16)) & 0xFFFFu)

// Fp16 histories saturate instead of overflowing to +inf.
float to_history(float v) {
#ifdef FOVRT_FP16
    return clamp(v, -FOVRT_HALF_SATURATION, FOVRT_HALF_SATURATION);
#else
    return v;
#endif
}
vec2 to_history(vec2 v) { return vec2(to_history(v.x), to_history(v.y)); }
vec3 to_history(vec3 v) { return vec3(to_history(v.x), to_history(v.y), to_history(v.z)); }
vec4 to_history(vec4 v) { return vec4(to_history(v.xyz), to_history(v.w)); }
// An (illumination, variance) texel as the ping-pong planes store it. A macro: a function
// returning f16vec4 would need 16-bit arithmetic (the Float16 capability), not only storage.
#define TO_ILLUM(v) hvec4(to_history(v))

#endif
