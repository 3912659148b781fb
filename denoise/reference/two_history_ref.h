// C++ reference stages of two-history SVGF (Tu 2024), A-SVGF (Schied et al. 2018, §3) and
// their combination two-history-asvgf. One function per new stage, each mirroring a shader
// (shaders/two_history_*.comp); the SVGF stages (variance estimate, à-trous, modulation) are the
// svgf_ref ones. The pass plan (denoise/svgf_family_plan.cpp) composes them, and
// SvgfFamilyReferenceDenoiser (svgf_family_ref.h) runs that list:
//
//   [asvgf_*: per-pixel α]  → two_history_reproject (both histories, weights, power sums, g)
//   → svgf_filter_moments on both → two_history_gradient (edge-aware g → q)
//   → svgf_atrous iteration 1 on both (feedback) → two_history_blend → svgf_atrous 2..N → modulate
//
// `asvgf` keeps only the unweighted history (SVGF with A-SVGF's per-pixel α).
//
// Choices the papers leave open (no paper has measured two-history-asvgf):
// - Warm-up: β = min(1, (1/α − 1)/W_u,prev), i.e. SVGF's α' = max(α, 1/historyLength) in weight
//   form; W_u doubles as the history length of the variance test (spatial estimate below 4), so
//   an A-SVGF α near 1 (history dropped) falls back to the spatial variance estimate by itself.
// - Both histories use the unweighted moments' variance as their à-trous guide; the blend's
//   variance is lerp(Var_w, Var_u, t), an upper bound of the variance of the lerp.
// - g is one EMA of the summed illumination (direct + indirect); q uses Σ_c Var_c. g is stored
//   as one float, the signed luminance of the gradient (exact for the EMA and the linear filter,
//   lum() being linear); q uses |lum(g)| for the thesis's lum(|g|) (equal where R, G, B change
//   with one sign, smaller otherwise). This keeps the extra history at the thesis's 88 B/pixel
//   with direct and indirect filtered separately.
// - two-history-asvgf does not keep g (its q is λ̂).
// - g is filtered by one 5×5 à-trous-kernel pass with w_z·w_n (no luminance term).
// - two-history-asvgf: β = 1 − α_i(p) (α_i from the A-SVGF gradient, base α = asvgf.alpha) for
//   both histories and their moments, and q = λ̂(p) (the same 3×3-strata max that gives α_i):
//   a measured temporal change pushes the blend to the unweighted history in proportion to its
//   relative size, the role the EMA gradient plays in two-history.
// - The anti-lag variants (asvgf-antilag, two-history-asvgf-antilag) take SVGF's base α and turn
//   λ into a history-length reduction (AntilagAlpha, after Q2RTX's asvgf_temporal): both
//   histories decay with the same β, so I_w, W_w and S_k shrink with W_u.
// - Feedback after à-trous iteration k > 1 is impossible for the two-history variants (the blend
//   would feed back); they feed back iteration 1 (or the unfiltered accumulation for k = 0).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/frame_inputs.h"
#include "core/image.h"
#include "denoise/denoiser.h"
#include "denoise/history_window.h"
#include "denoise/params.h"
#include "denoise/reference/svgf_ref.h"

namespace fovrt {

// Persistent per-pixel state of one frame (one side of the A/B pair). Channel 0 is direct (or the
// combined illumination), channel 1 indirect.
struct TwoHistoryState {
    std::array<Plane<vec3>, 2> iu;       // unweighted colour history I_u
    std::array<Plane<vec3>, 2> iw;       // weighted colour history I_w (two-history only)
    std::array<Plane<vec2>, 2> moments;  // luminance moments of the unweighted history
    Plane<float> wu;                     // W_u (also the "history length" of the variance test)
    Plane<float> ww;                     // W_w (two-history only)
    Plane<vec3> powerSums;               // (S_{-1}, S_0, S_1) (two-history only)
    Plane<float> gradient;  // EMA luminance gradient g of the summed illumination (two-history)
    // iw, ww and powerSums hold the weighted history's window of `window` pixels (0: the image).
    void Allocate(int width, int height, int channels, bool twoHistory, bool gradient, ivec2 window = ivec2(0));
};

struct TwoHistoryReprojectOptions {
    float alpha = 0.2f;              // temporal α of colour (ignored where alphaMap is given)
    float alphaMoments = 0.2f;       // temporal α of moments (ignored where alphaMap is given)
    float gradientBeta = 0.8f;       // β_g
    bool twoHistory = true;          // also accumulate I_w, W_w and S_k
    // One history (asvgf): a pixel with n = 0 keeps its history (TH_REPROJECT_FLAG_ZERO_SAMPLES);
    // the two-history variants always do.
    bool zeroSamples = false;
    bool gradient = true;            // and g (two-history only)
    bool writeColorHistory = false;  // feed back the unfiltered accumulation (no à-trous feedback)
    // Anti-lag variants: alphaMap holds the anti-lag factor a; α = AntilagAlpha(a, alpha, W_u,prev,
    // antilagPower) and α of moments lerp(alphaMoments, 1, a) (two_history_math.h).
    bool antilag = false;
    float antilagPower = 10.0f;
    // Firefly variants: each sample is clamped to max(μ + fireflySigma·σ of its reprojected moments,
    // its neighbours' largest sample luminance) before accumulation (SuppressFirefly, two_history_math.h).
    bool suppressFireflies = false;
    float fireflySigma = TwoHistoryParams{}.fireflySigma;
    Precision precision = Precision::Fp32;
    // The weighted history's window this frame and the previous one (size 0: the image). Outside
    // `window` illumW = illumU and nothing weighted is stored; a pixel inside whose taps are not
    // all in `prevWindow` restarts its weighted history from the reprojected I_u.
    HistoryWindow window, prevWindow;
};

// Stage two_history_reproject. colors[c] (c < channels) is channel c's demodulated illumination;
// with channels == 1 and color2 non-null, color2 is added (combined filtering). alphaMap, when
// non-null, is the per-pixel α of colour and moments (A-SVGF). Writes cur's accumulation state,
// illumU[c] = (I_u, Var) and, for two-history, illumW[c] = (I_w, Var) (Var of the unweighted
// moments: the edge-stopping guide of both histories).
void TwoHistoryReprojectRef(const std::array<const Plane<vec3>*, 2>& colors, int channels,
                            const Plane<vec3>* color2, const FrameInputs& frame,
                            const SvgfGeometry& prevGeometry, bool hasPrev,
                            const TwoHistoryState& prev, TwoHistoryState& cur,
                            const Plane<float>* alphaMap, std::array<Plane<vec4>, 2>& illumU,
                            std::array<Plane<vec4>, 2>& illumW,
                            const TwoHistoryReprojectOptions& options, DenoiseStats& stats);

// Stage two_history_gradient: 5×5 à-trous-kernel filter of g with w_z·w_n (edge-aware, no
// luminance term), then q = clamp(S·|g|/std(lum(I_u)), 0, 1) with Var(lum I_u) = Σ_c
// illumU[c].a.
void TwoHistoryGradientRef(const Plane<float>& gradient, const std::array<Plane<vec4>, 2>& illumU,
                           int channels, const FrameInputs& frame, const SvgfParams& svgf,
                           float qScale, Plane<float>& qOut);

// The filter of that stage at pixel (x, y) (not a background pixel). Instantiated for float (the
// stored luminance gradient) and vec3 (tests: the RGB gradient of Tu 2024's q).
template <typename T>
T FilterTwoHistoryGradient(const Plane<T>& gradient, const FrameInputs& frame,
                           const SvgfParams& svgf, int x, int y);

// The clamp variants' blend (TwoHistoryClampBlend): k of the box, off by default.
struct TwoHistoryClampOptions {
    bool enabled = false;
    float sigma = TwoHistoryParams{}.clampSigma;
};

// Stage two_history_blend: p from (W_u, W_w, S_k), t = p + q − pq,
// out = lerp(illumW, illumU, t) for colour and variance (lerp of variances bounds the variance of
// the lerp of correlated estimates from above). With `clamp` enabled, the clamp variants' blend
// replaces p: TwoHistoryClampBlend with the mean and σ of illumW's in-image 3×3 neighbourhood.
// With `heldChoice` (the hysteresis variants: TwoHistoryChoiceRef's output) it is p. ww and
// powerSums hold `window` (size 0: the image); outside it out = illumU.
void TwoHistoryBlendRef(const Plane<vec4>& illumU, const Plane<vec4>& illumW,
                        const Plane<float>& wu, const Plane<float>& ww,
                        const Plane<vec3>& powerSums, const Plane<float>& q, Plane<vec4>& out,
                        const TwoHistoryClampOptions& clamp = {}, const Plane<float>* heldChoice = nullptr,
                        const HistoryWindow& window = {});

// Mean and standard deviation per component of `plane`'s colour over (x, y)'s in-image 3×3
// neighbourhood (the clamp variants' box).
void NeighbourhoodMeanSigma(const Plane<vec4>& plane, int x, int y, vec3& mean, vec3& sigma);

}  // namespace fovrt
