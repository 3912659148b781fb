// Two-history SVGF per-pixel maths (SPEC §5, Tu 2024); mirrors denoise/reference/two_history_math.h line by
// line (TwoHistoryDecay, AntilagAlpha, SuppressFirefly, AccumulateWeights, TwoHistoryOptimalBlend,
// HystereticChoice, TwoHistoryGradientBlend, ClampToHistoryBox, TwoHistoryClampBlend).
// Weights are packed as (W_u, W_w) and power sums as (S_{-1}, S_0, S_1).
#ifndef FOVRT_TWO_HISTORY_GLSL
#define FOVRT_TWO_HISTORY_GLSL
#include "common/luminance.glsl"
#include "common/two_history_constants.glsl"

// β = min(1, (1/α − 1)/W_u,prev): steady state 1 − α, SVGF's max(α, 1/length) during warm-up.
float two_history_decay(float alpha, float wu_prev) {
    alpha = clamp(alpha, 1e-4, 1.0);
    if (wu_prev <= 0.0) return 0.0;
    return min(1.0, (1.0 / alpha - 1.0) / wu_prev);
}

// Anti-lag: the history length shrinks by (1 − a)^power, SVGF's warm-up runs on the shrunk length,
// and a pulls the weight to 1 (AntilagAlpha).
float antilag_alpha(float a, float alpha, float wu_prev, float power) {
    float keep = power > 0.0 ? pow(max(1.0 - a, 0.0), power) : 1.0;
    float warm = max(alpha, 1.0 / (wu_prev * keep + 1.0));
    return warm + (1.0 - warm) * a;
}

// Firefly suppression (FIREFLY flag): a sample of luminance l above both μ + kσ of the
// reprojected luminance moments (μ, μ₂) and its neighbours' largest sample luminance is scaled
// down to the larger of the two, hue kept (SuppressFirefly).
vec3 suppress_firefly(vec3 x, float l, vec2 m_prev, float k, float neighbour_max) {
    float temporal = m_prev.x + k * sqrt(max(m_prev.y - m_prev.x * m_prev.x, 0.0));
    float bound = max(temporal, neighbour_max);
    return l > bound ? x * (bound / l) : x;
}

// A neighbour's sample luminance, sanitised without counting (FireflyNeighbourLuminance).
float firefly_neighbour_luminance(vec3 c) {
    if (any(isnan(c)) || any(isinf(c))) return 0.0;
    return luminance(max(c, vec3(0.0)));
}

// p = clamp((a − b)/(a − 2b + c), 0, 1) with a = S_1/W_w², b = S_0/(W_w W_u), c = S_{-1}/W_u²;
// p = 1 at a tie (FOVRT_TWO_HISTORY_TIE).
float two_history_optimal_blend(float wu, float ww, vec3 s) {
    if (wu <= 0.0 || ww <= 0.0) return 1.0;
    float a = s.z / (ww * ww);
    float b = s.y / (ww * wu);
    float c = s.x / (wu * wu);
    float den = a - 2.0 * b + c;
    if (!(den > 1e-6 * (a + c))) return c - a > FOVRT_TWO_HISTORY_TIE * (a + c) ? 0.0 : 1.0;
    return clamp((a - b) / den, 0.0, 1.0);
}

// The hysteresis variants' held choice: prev moves towards p by rate × p's excess over ± band,
// clamped to [0, 1] (HystereticChoice).
float hysteretic_choice(float prev, float p, float rate, float band) {
    float d = p - prev;
    float excess = max(abs(d) - band, 0.0);
    return clamp(prev + rate * (d < 0.0 ? -excess : excess), 0.0, 1.0);
}

// q = clamp(S · |g| / std(lum I_u), 0, 1), g the filtered signed luminance gradient.
float two_history_gradient_blend(float g, float variance_lum_iu, float scale) {
    float abs_g = abs(g);
    float sd = sqrt(max(variance_lum_iu, 0.0));
    if (abs_g <= 0.0) return 0.0;
    return clamp(scale * abs_g / max(sd, 1e-8), 0.0, 1.0);
}

// The clamp variants: I_u kept inside I_w's 3×3 mean ± kσ, the box widened to hold I_w
// (ClampToHistoryBox); then lerp(clamped, I_u, q) and lerp(Var_w, Var_u, q) (TwoHistoryClampBlend).
vec3 clamp_to_history_box(vec3 iu, vec3 iw, vec3 mean, vec3 sigma, float k) {
    return clamp(iu, min(mean - k * sigma, iw), max(mean + k * sigma, iw));
}

vec4 two_history_clamp_blend(vec4 iu, vec4 iw, vec3 mean, vec3 sigma, float k, float q) {
    vec3 c = clamp_to_history_box(iu.rgb, iw.rgb, mean, sigma, k);
    return vec4(mix(c, iu.rgb, q), mix(iw.w, iu.w, q));
}

#endif
