// Two-history SVGF per-pixel maths (Tu 2024): the unweighted (I_u, W_u) and
// sample-count-weighted (I_w, W_w) exponential histories, the power sums S_k of the sample counts,
// the variance-optimal blend factor p, the (luminance) gradient EMA and the gradient-guided
// factor q.
// Header-only; the closed forms the shaders evaluate too are written once, for GLSL and C++, in
// shaders/common/two_history.glsl, and the functions here that call them carry their reasons.
// The accumulation is templated on the colour type for the tests. The Vulkan host includes this
// header too (no link dependency) for its debug view p, evaluated from the state it downloads.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "shaders/common/two_history.glsl"

namespace fovrt {

// Per-pixel accumulation state (the thesis's "total weights" float2 and "power sums" float3).
struct TwoHistoryWeights {
    float wu = 0.0f;       // W_u = Σ β^(t-i)
    float ww = 0.0f;       // W_w = Σ β^(t-i) n_i
    float sMinus1 = 0.0f;  // S_{-1} = Σ β^{2(t-i)} / n_i
    float s0 = 0.0f;       // S_0  = Σ β^{2(t-i)}
    float s1 = 0.0f;       // S_1  = Σ β^{2(t-i)} n_i
};

// One pixel's state as the histories store it: W_u, W_w and the power sums (S_{-1}, S_0, S_1).
inline TwoHistoryWeights StoredTwoHistoryWeights(float wu, float ww, const vec3& powerSums) {
    TwoHistoryWeights w;
    w.wu = wu;
    w.ww = ww;
    w.sMinus1 = powerSums.x, w.s0 = powerSums.y, w.s1 = powerSums.z;
    return w;
}

// Decay β of this frame for temporal weight α. The steady state is β = 1 − α (Tu 2024); during
// warm-up SVGF uses α' = max(α, 1/historyLength) (Falcor's SVGFPass). In weight form that is "W_u
// grows by one per frame but never beyond 1/α": β = min(1, (1/α − 1) / W_u,prev). With a
// constant α this reproduces SVGF's effective α exactly (1, 1/2, …, 1/len, then α), and the
// recursions below stay exact for a time-varying β, so the blend formula keeps holding.
inline float TwoHistoryDecay(float alpha, float wuPrev) {
    return glsl::two_history_decay(alpha, wuPrev);
}

// The anti-lag variants' α (Q2RTX's history-length reduction in weight form): the anti-lag factor
// a shrinks the history length W_u,prev to W_u,prev·(1 − a)^power, SVGF's warm-up max(α, 1/(length
// + 1)) runs on the shrunk length, and a pulls the weight to 1: α' = lerp(warm-up α, 1, a). As
// α' ≥ max(α, 1/(W_u,prev + 1)), TwoHistoryDecay(α', W_u,prev) gives W_u = 1/α': the history keeps
// counting from the shrunk length, so the frames after a change average as 1/2, 1/3, … and not
// with the base α. a = 0 is SVGF's warm-up; power = 0 keeps the length (Schied's α = lerp(α, 1,
// a)).
inline float AntilagAlpha(float a, float alpha, float wuPrev, float power) {
    return glsl::antilag_alpha(a, alpha, wuPrev, power);
}

// Firefly suppression before accumulation (the firefly variants). A sample of luminance l is an
// outlier when it exceeds both the pixel's own past, μ + kσ of its reprojected luminance moments
// (μ, μ₂), and every one of its 8 neighbours' samples this frame (`neighbourMax`): the temporal
// bound alone would lock a pixel out of a real brightening (a light switched on: σ = 0), the
// spatial one alone (ReBLUR's anti-firefly) would flatten a one-pixel highlight that was always
// there. The outlier is scaled down to the larger bound, keeping its hue. Applied where the
// moments span FOVRT_FIREFLY_MIN_HISTORY frames; biased (it removes energy) by design.
inline vec3 SuppressFirefly(const vec3& x, float l, const vec2& momentsPrev, float k,
                            float neighbourMax) {
    return glsl::suppress_firefly(x, l, momentsPrev, k, neighbourMax);
}

// A neighbour's sample luminance for the spatial bound: sanitised as the accumulation sanitises
// (non-finite → 0, negative components → 0), without counting.
inline float FireflyNeighbourLuminance(const vec3& c) {
    return glsl::firefly_neighbour_luminance(c);
}

// W_u ← βW_u + 1, W_w ← βW_w + n, S_k ← β²S_k + n^k.
inline TwoHistoryWeights AccumulateWeights(const TwoHistoryWeights& prev, float beta, float n) {
    TwoHistoryWeights w;
    const float b2 = beta * beta;
    w.wu = beta * prev.wu + 1.0f;
    w.ww = beta * prev.ww + n;
    w.sMinus1 = b2 * prev.sMinus1 + 1.0f / n;
    w.s0 = b2 * prev.s0 + 1.0f;
    w.s1 = b2 * prev.s1 + n;
    return w;
}

// I_u ← I_u + (x − I_u)/W_u, with W_u the updated weight.
template <typename T>
T AccumulateUnweighted(const T& prev, const T& x, float wuNew) {
    return prev + (x - prev) * (1.0f / wuNew);
}

// I_w ← I_w + n(x − I_w)/W_w, with W_w the updated weight.
template <typename T>
T AccumulateWeighted(const T& prev, const T& x, float n, float wwNew) {
    return prev + (x - prev) * (n / wwNew);
}

// Variance of lerp(I_w, I_u, p) in units of Var(X) (one sample's variance):
// V(p) = (1−p)² S_1/W_w² + 2p(1−p) S_0/(W_w W_u) + p² S_{−1}/W_u².
inline double TwoHistoryBlendVariance(const TwoHistoryWeights& w, double p) {
    const double a = double(w.s1) / (double(w.ww) * w.ww);
    const double b = double(w.s0) / (double(w.ww) * w.wu);
    const double c = double(w.sMinus1) / (double(w.wu) * w.wu);
    return (1 - p) * (1 - p) * a + 2 * p * (1 - p) * b + p * p * c;
}

// p = clamp((W_u²S_1 − W_uW_wS_0) / (W_u²S_1 − 2W_uW_wS_0 + W_w²S_{−1}), 0, 1) (Tu 2024, slides
// "First Phase of Blending": the boxed formula swaps S_0 and S_1; this one follows from the proof).
// Evaluated as (a − b)/(a − 2b + c) with the terms of V(p) above, which keeps the magnitudes near
// 1/W. The denominator is Σβ²(1/W_u − n/W_w)²/n ≥ 0 and vanishes only when every n is equal (I_w =
// I_u, any p is right); when it is lost in rounding V(p) is linear and the smaller end wins, and
// ends within FOVRT_TWO_HISTORY_TIE are a tie, p = 1 — on the device too, whatever the last bits
// of a and c (every n equal gives a = b = c).
inline float TwoHistoryOptimalBlend(const TwoHistoryWeights& w) {
    return glsl::two_history_optimal_blend(w.wu, w.ww, vec3(w.sMinus1, w.s0, w.s1));
}

// Gradient EMA g ← β_g g + (1 − β_g)(x − I_u,prev); g = 0 where the history was dropped.
// Templated for the tests; fovrt stores the signed luminance g = lum(x − I_u,prev) EMA (one float
// per pixel, LuminanceGradient below) instead of RGB: lum() is linear, so the EMA and the linear
// edge-aware filter give exactly lum() of the RGB gradient's EMA and filter.
template <typename T>
T AccumulateGradient(const T& gPrev, const T& x, const T& iuPrev, float betaG, bool hasHistory) {
    if (!hasHistory) return x * 0.0f;
    return gPrev * betaG + (x - iuPrev) * (1.0f - betaG);
}

// The stored gradient's per-frame input: lum(x − I_u,prev), signed.
inline float LuminanceGradient(const vec3& x, const vec3& iuPrev) { return Luminance(x - iuPrev); }

// q = clamp(S · |g| / std(lum(I_u)), 0, 1) with g the (filtered) luminance gradient. Tu 2024 writes
// lum(|g|) for an RGB g; |lum(g)| equals it where the R, G, B gradients share a sign (e.g. a light
// switching on or off) and is smaller otherwise (a hue change at constant luminance
// gives q ≈ 0).
inline float TwoHistoryGradientBlend(float g, float varianceLumIu, float scale) {
    return glsl::two_history_gradient_blend(g, varianceLumIu, scale);
}

// I_b = lerp(I_opt, I_u, q) = lerp(I_w, I_u, t) with t = p + q − pq.
inline float TwoHistoryFinalBlend(float p, float q) { return p + q - p * q; }

// The hysteresis variants' held choice (a temporally filtered, hysteretic p): the reprojected
// previous choice moves towards this frame's p by `rate` times p's excess over a dead band of
// ± `band`, so a p that jitters within the band is held and a flip (a fovea entering: p jumps by
// ~0.6) is spread over ~1/rate frames. rate 1 with band 0 returns p; the result lies between
// the previous choice and p, clamped to [0, 1] (a bilinearly reprojected previous choice may
// round a hair outside). q is not filtered: t = held + q − held·q still hands a changing pixel
// to I_u at once.
inline float HystereticChoice(float prev, float p, float rate, float band) {
    return glsl::hysteretic_choice(prev, p, rate, band);
}

// The clamp variants' blend in place of p (NRD ReLAX clamps one history to the other's local
// mean ± kσ): I_u is kept where it lies inside the box of I_w's 3×3 neighbourhood, mean ± kσ per
// component (`mean`, `sigma`), and moved to the box's face otherwise. The box is widened to hold
// I_w itself, so where the histories agree (every sample had the same count) I_u passes
// unchanged. No per-pixel choice that flips when the sample count does: I_u moves only by its
// excess over the neighbourhood's spread.
inline vec3 ClampToHistoryBox(const vec3& iu, const vec3& iw, const vec3& mean, const vec3& sigma,
                              float k) {
    return glsl::clamp_to_history_box(iu, iw, mean, sigma, k);
}

// The clamp variants' output: lerp(clamped I_u, I_u, q) for colour (q still hands a changing pixel
// to I_u, as in t = p + q − pq), lerp(Var_w, Var_u, q) for the variance (the clamped estimate's
// spread is the weighted history's where q = 0).
inline vec4 TwoHistoryClampBlend(const vec4& iu, const vec4& iw, const vec3& mean,
                                 const vec3& sigma, float k, float q) {
    return glsl::two_history_clamp_blend(iu, iw, mean, sigma, k, q);
}

}  // namespace fovrt
