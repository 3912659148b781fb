// Rec.709 luminance (Falcor SVGF, SPEC §3); same weights as fovrt::Luminance in core/math.h.
#ifndef FOVRT_LUMINANCE_GLSL
#define FOVRT_LUMINANCE_GLSL
float luminance(vec3 rgb) { return dot(rgb, vec3(0.2126, 0.7152, 0.0722)); }
#endif
