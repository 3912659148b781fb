// Octahedral unit normals (Cigolle et al. 2014, "A Survey of Efficient Representations for
// Independent Unit Vectors"): fp16 storage keeps the geometry's normals as two signed 16-bit
// integers per pixel, 4 bytes instead of 12 (denoise/planes.h, INPUT_NORMAL). The host encodes
// (OctahedralCode, denoise/planes.cpp); the decoding is written once for GLSL and C++
// (shared_language.glsl): the shaders read normals through FETCH_NORMAL (access.glsl), the C++
// reference rounds its copy of the inputs through the same function. (−32768, −32768) holds a zero
// normal (background), which the octahedron cannot.
#ifndef FOVRT_OCTAHEDRAL_NORMAL_GLSL
#define FOVRT_OCTAHEDRAL_NORMAL_GLSL
#include "shared_language.glsl"

FOVRT_GLSL_BEGIN

FOVRT_SHARED_FN vec3 octahedral_normal(ivec2 code) {
    if (code.x == -32768 && code.y == -32768) return vec3(0.0f);
    vec2 p = vec2(code) / 32767.0f;
    vec3 n = vec3(p.x, p.y, 1.0f - abs(p.x) - abs(p.y));
    if (n.z < 0.0f) {  // the lower hemisphere, folded over the diagonals
        vec2 folded = (vec2(1.0f) - abs(vec2(n.y, n.x))) * vec2(n.x >= 0.0f ? 1.0f : -1.0f, n.y >= 0.0f ? 1.0f : -1.0f);
        n = vec3(folded.x, folded.y, n.z);
    }
    return normalize(n);
}

FOVRT_GLSL_END

#endif
