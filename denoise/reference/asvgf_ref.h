// C++ reference of the A-SVGF temporal-gradient stages (Schied et al. 2018, §3), one function
// per stage with the inputs and outputs of its shader (shaders/asvgf_*.comp):
//   asvgf_gradient_scatter  gradient samples → per 3×3 stratum (δ, Δ) + stratum guide
//   asvgf_gradient_atrous   5 iterations of a joint-bilateral 3×3-box à-trous on (δ, Δ)
//   asvgf_alpha             λ = min(1, |δ̂|/Δ̂), α_s = (1−λ)α + λ, per pixel max over 3×3 strata
//                           (anti-lag variants: a = clamp(gain·λ, 0, 1) in α's place)
// The per-pixel α drives the temporal accumulation of colour and moments (asvgf and
// two-history-asvgf, denoise/reference/two_history_ref.h).
#pragma once

#include <optional>

#include "core/frame_inputs.h"
#include "core/image.h"
#include "core/math.h"
#include "denoise/gradient_strata.h"
#include "denoise/params.h"

namespace fovrt {

// Guide of one stratum: the geometry and colour luminance of the pixel that carries its gradient
// sample (the stratum's centre pixel when it has none).
struct StratumGuide {
    float depth = 0.0f;
    vec3 normal{0.0f};
    vec2 depthGradient{0.0f};  // per pixel
    float luminance = 0.0f;    // luminance of the noisy colour at that pixel
    uint32_t objectId = kNoObject;
};

// Stage asvgf_gradient_scatter. gradient(s) = (δ, Δ) = (new − old, max(new, old)) of the first
// sample landing in stratum s (0 for empty strata); samples outside the grid are ignored.
// Returns how many strata received a sample.
int AsvgfScatterGradientsRef(const FrameInputs& frame, Plane<vec2>& gradient,
                             Plane<StratumGuide>& guide);

// Stage asvgf_gradient_atrous, iteration i (step 2^i strata): 3×3 box kernel with SVGF weights
// w_z·w_n·w_l on the stratum guide; w_l is scaled by the 3×3-stratum standard deviation of the
// guide luminance (the stratum analogue of SVGF's variance). Empty strata enter as 0.
void AsvgfGradientAtrousRef(const Plane<vec2>& in, const Plane<StratumGuide>& guide, int iteration,
                            Plane<vec2>& out, const SvgfParams& svgf);

// Stage asvgf_alpha: per-pixel temporal α (and λ, the same max over 3×3 strata) for W×H. With
// `antilagGain` (the anti-lag variants) alphaOut holds the anti-lag factor a = clamp(gain·λ, 0, 1)
// instead; two_history_reproject turns it into α with the history length (AntilagAlpha).
void AsvgfAlphaRef(const Plane<vec2>& reconstructed, int width, int height, float alpha,
                   Plane<float>& alphaOut, Plane<float>& lambdaOut,
                   std::optional<float> antilagGain = std::nullopt);

// The three stages in order (gradientIterations à-trous iterations). `reconstructed` receives
// (δ̂, Δ̂) per stratum.
void AsvgfTemporalAlphaRef(const FrameInputs& frame, const AsvgfParams& params,
                           const SvgfParams& svgf, Plane<float>& alphaOut, Plane<float>& lambdaOut,
                           Plane<vec2>* reconstructed = nullptr);

}  // namespace fovrt
