// A-SVGF shared declarations (SPEC §4): the gradient sample as uploaded from
// fovrt::GradientSample (32 bytes, std430) and the stratum size.
#ifndef FOVRT_ASVGF_GLSL
#define FOVRT_ASVGF_GLSL
#define ASVGF_STRATUM_SIZE 3  // fovrt::kGradientStratumSize
struct GradientSample {
    ivec2 stratum;
    ivec2 pixel;
    ivec2 prev_pixel;
    float new_luminance;
    float old_luminance;
};
#endif
