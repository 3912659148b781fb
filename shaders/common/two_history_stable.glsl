// two-history-stable's luminance stabilisation (denoise/two_history_stable.md), written once for
// GLSL and C++ (shared_language.glsl): the shader calls these functions, the C++ reference through
// denoise/reference/two_history_stable_ref.h (StabilizationWeight, StabilizationChangeWeight,
// StabilizedLuminance, StabilizedColor), which documents each one.
#ifndef FOVRT_TWO_HISTORY_STABLE_GLSL
#define FOVRT_TWO_HISTORY_STABLE_GLSL
#include "shared_language.glsl"
#include "two_history_constants.glsl"

FOVRT_GLSL_BEGIN

// The weight max(α_s, 1/W_u, change): W_u (the accumulation's history length) restarts the
// stabilisation with the accumulation; `change` (two-history-stable-antilag) follows changing light.
FOVRT_SHARED_FN float stabilization_weight(float alpha_s, float wu, float change) {
    return max(max(alpha_s, 1.0f / max(wu, 1.0f)), change);
}

// (q − q0)/(1 − q0) in [0, 1].
FOVRT_SHARED_FN float stabilization_change_weight(float q, float q0) {
    return clamp((q - q0) / (1.0f - q0), 0.0f, 1.0f);
}

// L_s = lerp(clamp(L_s,prev, m − kσ, m + kσ), L, a): the history may differ from the
// neighbourhood by k standard deviations of the estimate before it counts as lag.
FOVRT_SHARED_FN float stabilized_luminance(float history, float l, float mean, float sigma, float k, float a) {
    float h = clamp(history, mean - k * sigma, mean + k * sigma);
    return mix(h, l, a);
}

// The colour with luminance L_s and the hue of c (luminance L).
FOVRT_SHARED_FN vec3 stabilized_color(vec3 c, float l, float ls) {
    return l > float(FOVRT_STABLE_LUMINANCE_FLOOR) ? c * (ls / l) : c + vec3(ls - l);
}

FOVRT_GLSL_END

#endif
