// The denoisers: every name `run`, `experiment`, `bench` and `memory` accept, read into the row the
// passes run from (the family, the mechanisms it turns on, what it needs from the renderer).
//
// A name is a family and mechanisms joined by '+', in any order: `two-history+stabilize+clamp`,
// `svgf+asvgf+antilag`, `rae+spp`. The canonical form (CanonicalDenoiserName) writes the family,
// then the mechanisms in the order a frame runs them. Each mechanism declares the families it
// joins, the mechanism it requires and the one it excludes (kMechanisms in variants.cpp); a name
// that breaks a rule is refused in one line naming the rule. What the renderer must produce is
// derived from the mechanisms, never stored. Today's names (svgf-weighted, two-history-stable, …)
// are aliases of compositions, in one table (kAliases), and may stand in a name for theirs
// (`two-history-stable+clamp`).
//
// Every name also takes a demodulation: "+brdf" filters illumination demodulated by the BRDF
// pre-integration F_β, "+albedo" by the albedo (Zhuang et al. §4.3: the filter is a black box,
// only the demodulation factor changes; denoise/demodulation.h). A name without one filters what
// the tracer wrote (render.demodulation, default albedo). The demodulation is no part of the row.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/frame_inputs.h"
#include "denoise/mechanism_slots.h"
#include "denoise/params.h"

namespace fovrt {

enum class PlaneKind : uint8_t;  // denoise/planes.h
enum class DebugViewId;         // denoise/debug_views.h

// The pass family a variant runs.
// Svgf: reproject → moments → à-trous → modulate (Schied et al. 2017, §4).
// TwoHistory: the same stages composed with A-SVGF's temporal gradient and/or two-history's
// second history (Schied et al. 2018; Tu 2024).
// Rae: the recurrent denoising autoencoder (Chaitanya et al. 2017): features → U-Net with
// recurrent blocks → remodulation; its weights come from denoise.rae.weights
// (denoise/rae_weights.h).
enum class DenoiserFamily { Svgf, TwoHistory, Rae };

// "svgf", "two-history", "rae": how `fovrt info` names a family.
std::string_view DenoiserFamilyName(DenoiserFamily family);

struct DenoiserVariant {
    std::string_view name;     // the factory name, e.g. "two-history-asvgf"
    std::string_view summary;  // one line for `fovrt info` and error messages
    DenoiserFamily family = DenoiserFamily::Svgf;
    bool weightBySampleCount = false;  // svgf-weighted: temporal weights × n (SvgfParams)
    bool twoHistory = false;     // keeps the weighted history I_w, W_w, S_k and blends (Tu 2024)
    bool emaGradient = false;    // two-history's EMA luminance gradient g → q
    bool asvgfGradient = false;  // A-SVGF temporal gradient → per-pixel α (Schied 2018)
    // Anti-lag (with asvgfGradient): a = clamp(gain·λ, 0, 1) shrinks the history length by
    // (1 − a)^power before SVGF's warm-up, then α = lerp(α, 1, a) (Q2RTX); base α is SVGF's.
    bool antilag = false;
    // Luminance stabilisation of the filtered illumination with its own history, clamped to the
    // neighbourhood's spread (two-history-stable, denoise/two_history_stable.md).
    bool stabilize = false;
    // Firefly suppression before accumulation: a sample brighter than both μ + kσ of its reprojected
    // luminance moments and all 8 neighbours' samples is scaled down to the larger bound
    // (k = denoise.two_history.firefly_sigma; two-history family only).
    bool suppressFireflies = false;
    // History clamping in place of the variance-optimal choice p (NRD ReLAX's clamp of one history
    // to the other's neighbourhood): the blend keeps I_u inside the box of I_w's 3×3 mean ± kσ,
    // widened to hold I_w, then q pulls it back to I_u (k = denoise.two_history.clamp_sigma).
    bool clampHistory = false;
    // With stabilize: the stabilisation weight rises to 1 where two-history's change detector q
    // exceeds denoise.two_history_stable.antilag_q, so the stabilised history follows changing light.
    bool stabilizeAntilag = false;
    // A temporally filtered, hysteretic history choice in place of p (two_history_choice): the held
    // choice follows p only by its excess over a dead band, at a rate (denoise.two_history.choice_rate,
    // choice_band); q still passes unfiltered.
    bool hystereticChoice = false;
    // What the renderer must produce for it (FrameInputs):
    bool needsGradientSamples = false;  // A-SVGF forward-projected gradient samples
    bool needsSampleCount = false;      // per-pixel sample counts uploaded to the device
    bool raeSampleCount = false;  // rae: the network with the sample-count input (weights_spp)
    bool raeBalance = false;      // rae: input balanced to grey, undone on the output (RaeBalanceGains)
};

// The aliases' rows, in the order tables list them.
const std::vector<DenoiserVariant>& DenoiserVariants();
// The family and mechanism tokens a name is written with, in table order.
std::vector<std::string> FamilyTokens();
std::vector<std::string> MechanismTokens();
// One line per mechanism token: what it does, the families it joins, what it requires and
// excludes, and why (docs/denoisers.md).
std::vector<std::string> MechanismRules();
// `name` written canonically: the family, the mechanisms in frame order, the demodulation last
// ("stabilize+two-history+brdf" → "two-history+stabilize+brdf"; an alias → its composition).
// fovrt::Error when `name` is none.
std::string CanonicalDenoiserName(std::string_view name);
// Every valid composition without a demodulation, canonical, family by family: what the tests
// walk.
std::vector<std::string> DenoiserCompositions();
// The row of `name`; fovrt::Error naming the key `what` (e.g. "denoise.denoisers"), listing the
// known names and suggesting the nearest one otherwise.
const DenoiserVariant& FindDenoiserVariant(std::string_view name,
                                           std::string_view what = "denoiser");
// Why `name` cannot be used, for callers that name the key themselves: an unknown part ("unknown
// denoiser 'x': ... did you mean 'y'?"), a broken rule ("'two-history+antilag': antilag requires
// asvgf (...)"), or a demodulation its family refuses (rae+brdf); nullopt when it can.
std::optional<std::string> DenoiserNameProblem(std::string_view name);
// Null when `name` is no denoiser. An alias gives its row; any other composition a row made once
// per canonical name and kept for the process (its name the canonical one, without demodulation).
const DenoiserVariant* LookupDenoiserVariant(std::string_view name);

// The demodulation a name asks for ("+brdf", "+albedo"); nullopt without one.
std::optional<Demodulation> DenoiserDemodulation(std::string_view name);

// What the renderer must produce for a set of variant names, from their rows and suffixes.
struct RendererNeeds {
    bool gradientSamples = false;  // some row's needsGradientSamples
    bool fbetaPlane = false;       // some "+brdf" name: FrameInputs::fbeta (RenderSettings::fbetaPlane)
};
// fovrt::Error naming the key `what` on an unknown name.
RendererNeeds RendererNeedsOf(const std::vector<std::string>& names, std::string_view what);

// The mechanisms a row turns on, by name, in the order the frame runs them ("weighted history",
// "A-SVGF gradient", …; none for plain SVGF): what `fovrt info --denoiser` prints. Read from the
// row's flags through the mechanism table (kMechanisms in variants.cpp).
std::vector<std::string> VariantMechanisms(const DenoiserVariant& variant);
// The settings (config keys) the row's passes read, in the order of the settings tables: its
// family's and its mechanisms' (kMechanisms in variants.cpp), less those a mechanism makes unread
// and those of a mechanism that changes nothing in this composition (stabilize-antilag with asvgf:
// MechanismRules says why).
// denoise.precision and denoise.device are every denoiser's and not listed.
std::vector<std::string> VariantSettings(const DenoiserVariant& variant);
// The kinds of plane (denoise/planes.h) the row's passes name: its family's and its mechanisms'
// (denoise_pass_plan_test holds them to every composition's plan); empty for the RAE.
std::vector<PlaneKind> VariantPlanes(const DenoiserVariant& variant);
// The debug views (denoise/debug_views.h) the row offers: its family's and its mechanisms', less
// those a mechanism takes away (the clamp replaces p). DebugViewNames lists them in table order.
std::vector<DebugViewId> VariantDebugViews(const DenoiserVariant& variant);
// What the renderer must produce for the row, in words (empty: the noisy inputs alone).
std::vector<std::string> VariantRendererNeeds(const DenoiserVariant& variant);

// A mechanism with passes of its own: its row's flag and what the row declares of its fragment.
struct MechanismFragment {
    bool DenoiserVariant::*flag;
    MechanismPasses passes;
};
// Every mechanism with passes of its own, in the order a frame runs them (the plan's tests).
std::vector<MechanismFragment> MechanismFragments();
// The passes of the mechanisms `variant` turns on at `slot`, in frame order (PlanSvgfFamily).
std::vector<MechanismPass> MechanismPassesAt(const DenoiserVariant& variant, FrameSlot slot);

// The aliases, in table order (every composition is accepted too).
const std::vector<std::string>& DenoiserNames();

// Names of the channels the SVGF stages filter (FilteredChannels, denoise/planes.h): {"direct",
// "indirect"}, or {"combined"} with filterCombined.
std::vector<std::string> SvgfChannels(const SvgfParams& params);

// Parameters the variant implies (svgf-weighted sets svgf.weightBySampleCount; the two-history
// family keeps its own weighted history and clears it).
DenoiserParams ParamsForVariant(const DenoiserVariant& variant, DenoiserParams params);

}  // namespace fovrt
