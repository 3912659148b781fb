// The dialect of the per-pixel functions written once for GLSL and C++ (luminance.glsl,
// two_history.glsl): GLSL 4.5 that also compiles as C++ over GLM, whose vector types and functions
// (those listed in FOVRT_GLSL_BEGIN) are GLSL's. C++ sees the functions in
// namespace fovrt::glsl. Rules of the dialect: float literals carry the `f` suffix (GLM's
// templates take one type), no swizzles beyond .x/.y/.z/.w (vec3(v4) takes the first three), no
// `in`/`out` parameters, and every function is declared with FOVRT_SHARED_FN.
#ifndef FOVRT_SHARED_LANGUAGE_GLSL
#define FOVRT_SHARED_LANGUAGE_GLSL

#ifdef __cplusplus
#include <glm/glm.hpp>
// Using-declarations, not a using-directive: GLSL's names are found in fovrt::glsl itself,
// whatever same-named functions an enclosing namespace holds.
#define FOVRT_GLSL_BEGIN \
    namespace fovrt::glsl { \
    using glm::abs, glm::any, glm::clamp, glm::dot, glm::exp, glm::exp2, glm::isinf, glm::isnan, glm::log2, glm::max, \
        glm::min, glm::mix, glm::normalize, glm::pow, glm::sqrt, glm::floatBitsToUint, glm::uintBitsToFloat; \
    using uint = unsigned int; \
    using glm::bvec3, glm::ivec2, glm::vec2, glm::vec3, glm::vec4;
#define FOVRT_GLSL_END }
#define FOVRT_SHARED_FN inline
#else
#define FOVRT_GLSL_BEGIN
#define FOVRT_GLSL_END
#define FOVRT_SHARED_FN
#endif

#endif
