// Two-history SVGF per-pixel maths (Tu 2024), written once for GLSL and C++ (shared_language.glsl):
// the shaders call these functions, the C++ reference calls them through
// denoise/reference/two_history_math.h, which documents each one (TwoHistoryDecay, AntilagAlpha,
// SuppressFirefly, FireflyNeighbourLuminance, TwoHistoryOptimalBlend, HystereticChoice,
// TwoHistoryGradientBlend, ClampToHistoryBox, TwoHistoryClampBlend).
// Weights are packed as (W_u, W_w) and power sums as (S_{-1}, S_0, S_1).
#ifndef FOVRT_TWO_HISTORY_GLSL
#define FOVRT_TWO_HISTORY_GLSL
#include "luminance.glsl"
#include "shared_language.glsl"
#include "two_history_constants.glsl"

FOVRT_GLSL_BEGIN

// β = min(1, (1/α − 1)/W_u,prev): steady state 1 − α, SVGF's max(α, 1/length) during warm-up.
FOVRT_SHARED_FN float two_history_decay(float alpha, float wu_prev) {
    alpha = clamp(alpha, 1e-4f, 1.0f);
    if (wu_prev <= 0.0f) return 0.0f;  // no history: nothing to decay
    return min(1.0f, (1.0f / alpha - 1.0f) / wu_prev);
}

// Anti-lag: the history length shrinks by (1 − a)^power, SVGF's warm-up runs on the shrunk length,
// and a pulls the weight to 1.
FOVRT_SHARED_FN float antilag_alpha(float a, float alpha, float wu_prev, float power) {
    float keep = power > 0.0f ? pow(max(1.0f - a, 0.0f), power) : 1.0f;
    float warm = max(alpha, 1.0f / (wu_prev * keep + 1.0f));
    return warm + (1.0f - warm) * a;
}

// Firefly suppression: a sample of luminance l above both μ + kσ of the reprojected luminance
// moments (μ, μ₂) and its neighbours' largest sample luminance is scaled down to the larger of
// the two, hue kept.
FOVRT_SHARED_FN vec3 suppress_firefly(vec3 x, float l, vec2 m_prev, float k, float neighbour_max) {
    float temporal = m_prev.x + k * sqrt(max(m_prev.y - m_prev.x * m_prev.x, 0.0f));
    float bound = max(temporal, neighbour_max);
    return l > bound ? x * (bound / l) : x;
}

// A neighbour's sample luminance, sanitised as the accumulation sanitises (non-finite → 0,
// negative components → 0), without counting.
FOVRT_SHARED_FN float firefly_neighbour_luminance(vec3 c) {
    if (any(isnan(c)) || any(isinf(c))) return 0.0f;
    return luminance(max(c, vec3(0.0f)));
}

// p = clamp((a − b)/(a − 2b + c), 0, 1) with a = S_1/W_w², b = S_0/(W_w W_u), c = S_{-1}/W_u²;
// p = 1 at a tie (FOVRT_TWO_HISTORY_TIE).
FOVRT_SHARED_FN float two_history_optimal_blend(float wu, float ww, vec3 s) {
    if (wu <= 0.0f || ww <= 0.0f) return 1.0f;
    float a = s.z / (ww * ww);
    float b = s.y / (ww * wu);
    float c = s.x / (wu * wu);
    float den = a - 2.0f * b + c;
    if (!(den > 1e-6f * (a + c))) return c - a > float(FOVRT_TWO_HISTORY_TIE) * (a + c) ? 0.0f : 1.0f;
    return clamp((a - b) / den, 0.0f, 1.0f);
}

// The hysteresis variants' held choice: prev moves towards p by rate × p's excess over ± band,
// clamped to [0, 1].
FOVRT_SHARED_FN float hysteretic_choice(float prev, float p, float rate, float band) {
    float d = p - prev;
    float excess = max(abs(d) - band, 0.0f);
    return clamp(prev + rate * (d < 0.0f ? -excess : excess), 0.0f, 1.0f);
}

// q = clamp(S · |g| / std(lum I_u), 0, 1), g the filtered signed luminance gradient.
FOVRT_SHARED_FN float two_history_gradient_blend(float g, float variance_lum_iu, float scale) {
    float abs_g = abs(g);
    float sd = sqrt(max(variance_lum_iu, 0.0f));
    if (abs_g <= 0.0f) return 0.0f;
    return clamp(scale * abs_g / max(sd, 1e-8f), 0.0f, 1.0f);
}

// The clamp variants: I_u kept inside I_w's 3×3 mean ± kσ, the box widened to hold I_w; then
// lerp(clamped, I_u, q) for colour and lerp(Var_w, Var_u, q) for the variance (w).
FOVRT_SHARED_FN vec3 clamp_to_history_box(vec3 iu, vec3 iw, vec3 mean, vec3 sigma, float k) {
    return clamp(iu, min(mean - k * sigma, iw), max(mean + k * sigma, iw));
}

FOVRT_SHARED_FN vec4 two_history_clamp_blend(vec4 iu, vec4 iw, vec3 mean, vec3 sigma, float k, float q) {
    vec3 c = clamp_to_history_box(vec3(iu), vec3(iw), mean, sigma, k);
    return vec4(mix(c, vec3(iu), q), mix(iw.w, iu.w, q));
}

FOVRT_GLSL_END

#endif
