// two-history-stable's luminance stabilisation (denoise/two_history_stable.md); mirrors
// denoise/reference/two_history_stable_ref.h (StabilizationWeight, StabilizationChangeWeight,
// StabilizedLuminance, StabilizedColor) line by line.
#ifndef FOVRT_TWO_HISTORY_STABLE_GLSL
#define FOVRT_TWO_HISTORY_STABLE_GLSL

// The weight max(α_s, 1/W_u, change) (StabilizationWeight): W_u (the accumulation's history
// length) restarts the stabilisation with the accumulation; `change` (two-history-stable-antilag)
// follows changing light.
float stabilization_weight(float alpha_s, float wu, float change) {
    return max(max(alpha_s, 1.0 / max(wu, 1.0)), change);
}

// (q − q0)/(1 − q0) in [0, 1] (StabilizationChangeWeight).
float stabilization_change_weight(float q, float q0) {
    return clamp((q - q0) / (1.0 - q0), 0.0, 1.0);
}

// L_s = lerp(clamp(L_s,prev, m − kσ, m + kσ), L, a): the history may differ from the
// neighbourhood by k standard deviations of the estimate before it counts as lag.
float stabilized_luminance(float history, float l, float mean, float sigma, float k, float a) {
    float h = clamp(history, mean - k * sigma, mean + k * sigma);
    return mix(h, l, a);
}

// The colour with luminance L_s and the hue of c (luminance L).
vec3 stabilized_color(vec3 c, float l, float ls) {
    return l > FOVRT_STABLE_LUMINANCE_FLOOR ? c * (ls / l) : c + vec3(ls - l);
}

#endif
