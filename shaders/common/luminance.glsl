// Rec.709 luminance, as Falcor's SVGF and the papers use; written once for GLSL and C++
// (shared_language.glsl; C++ calls it as fovrt::Luminance, src/core/math.h).
#ifndef FOVRT_LUMINANCE_GLSL
#define FOVRT_LUMINANCE_GLSL
#include "shared_language.glsl"  // from this folder, in both languages

FOVRT_GLSL_BEGIN
FOVRT_SHARED_FN float luminance(vec3 rgb) { return dot(rgb, vec3(0.2126f, 0.7152f, 0.0722f)); }
FOVRT_GLSL_END

#endif
