// two-history-stable's luminance stabilisation (denoise/two_history_stable.md); mirrors
// denoise/reference/two_history_stable_ref.h (StabilizedLuminance, StabilizedColor) line by line.
#ifndef FOVRT_TWO_HISTORY_STABLE_GLSL
#define FOVRT_TWO_HISTORY_STABLE_GLSL

// L_s = lerp(clamp(L_s,prev, m − kσ, m + kσ), L, max(α_s, 1/W_u)): the history may differ from the
// neighbourhood by k standard deviations of the estimate before it counts as lag; W_u (the
// accumulation's history length) restarts the stabilisation with the accumulation.
float stabilized_luminance(float history, float l, float mean, float sigma, float k, float alpha_s, float wu) {
    float h = clamp(history, mean - k * sigma, mean + k * sigma);
    return mix(h, l, max(alpha_s, 1.0 / max(wu, 1.0)));
}

// The colour with luminance L_s and the hue of c (luminance L).
vec3 stabilized_color(vec3 c, float l, float ls) {
    return l > FOVRT_STABLE_LUMINANCE_FLOOR ? c * (ls / l) : c + vec3(ls - l);
}

#endif
