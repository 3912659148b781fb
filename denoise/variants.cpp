#include "denoise/variants.h"

#include <fmt/format.h>

#include <algorithm>

#include "core/error.h"
#include "core/nearest_name.h"
#include "denoise/planes.h"

namespace fovrt {

const std::vector<DenoiserVariant>& DenoiserVariants() {
    using F = DenoiserFamily;
    static const std::vector<DenoiserVariant> rows = {
        {.name = "svgf", .summary = "SVGF (Schied 2017)", .family = F::Svgf},
        {.name = "svgf-weighted",
         .summary = "SVGF with temporal weights x sample count",
         .family = F::Svgf,
         .weightBySampleCount = true,
         .needsSampleCount = true},
        {.name = "asvgf",
         .summary = "A-SVGF temporal gradients (Schied 2018)",
         .family = F::TwoHistory,
         .asvgfGradient = true,
         .needsGradientSamples = true},
        {.name = "two-history",
         .summary = "two-history SVGF (Tu 2024)",
         .family = F::TwoHistory,
         .twoHistory = true,
         .emaGradient = true,
         .needsSampleCount = true},
        {.name = "two-history-asvgf",
         .summary = "two-history SVGF with A-SVGF's gradient as q",
         .family = F::TwoHistory,
         .twoHistory = true,
         .asvgfGradient = true,
         .needsGradientSamples = true,
         .needsSampleCount = true},
        // Anti-lag variants: the paper-faithful rows above, with λ shrinking the history length.
        {.name = "asvgf-antilag",
         .summary = "A-SVGF with gradient-driven history-length reduction (Q2RTX anti-lag), SVGF's base alpha",
         .family = F::TwoHistory,
         .asvgfGradient = true,
         .antilag = true,
         .needsGradientSamples = true},
        {.name = "two-history-asvgf-antilag",
         .summary = "two-history-asvgf with the anti-lag history-length reduction",
         .family = F::TwoHistory,
         .twoHistory = true,
         .asvgfGradient = true,
         .antilag = true,
         .needsGradientSamples = true,
         .needsSampleCount = true},
        {.name = "two-history-stable",
         .summary = "two-history SVGF with a clamped luminance stabilisation pass (less flicker)",
         .family = F::TwoHistory,
         .twoHistory = true,
         .emaGradient = true,
         .stabilize = true,
         .needsSampleCount = true},
        {.name = "two-history-stable-firefly",
         .summary = "two-history-stable with firefly suppression before accumulation (outliers vs their past and neighbours clamped)",
         .family = F::TwoHistory,
         .twoHistory = true,
         .emaGradient = true,
         .stabilize = true,
         .suppressFireflies = true,
         .needsSampleCount = true},
        {.name = "two-history-stable-antilag",
         .summary = "two-history-stable whose stabilisation follows two-history's change detector q (no lag under changing light)",
         .family = F::TwoHistory,
         .twoHistory = true,
         .emaGradient = true,
         .stabilize = true,
         .stabilizeAntilag = true,
         .needsSampleCount = true},
        {.name = "two-history-asvgf-stable-antilag",
         .summary = "two-history-asvgf-antilag with the stabilisation pass, its weight driven by A-SVGF's lambda",
         .family = F::TwoHistory,
         .twoHistory = true,
         .asvgfGradient = true,
         .antilag = true,
         .stabilize = true,
         .stabilizeAntilag = true,
         .needsGradientSamples = true,
         .needsSampleCount = true},
        {.name = "two-history-clamp",
         .summary = "two-history with I_u clamped to I_w's neighbourhood (mean +- k sigma) instead of the choice p",
         .family = F::TwoHistory,
         .twoHistory = true,
         .emaGradient = true,
         .clampHistory = true,
         .needsSampleCount = true},
        {.name = "two-history-stable-clamp",
         .summary = "two-history-clamp with two-history-stable's luminance stabilisation pass",
         .family = F::TwoHistory,
         .twoHistory = true,
         .emaGradient = true,
         .stabilize = true,
         .clampHistory = true,
         .needsSampleCount = true},
        {.name = "two-history-hysteresis",
         .summary = "two-history with a temporally filtered, hysteretic history choice p (held within a band, moved at a rate)",
         .family = F::TwoHistory,
         .twoHistory = true,
         .emaGradient = true,
         .hystereticChoice = true,
         .needsSampleCount = true},
        {.name = "two-history-stable-hysteresis",
         .summary = "two-history-hysteresis with two-history-stable's luminance stabilisation pass",
         .family = F::TwoHistory,
         .twoHistory = true,
         .emaGradient = true,
         .stabilize = true,
         .hystereticChoice = true,
         .needsSampleCount = true},
        {.name = "two-history-asvgf-stable-hysteresis",
         .summary = "two-history-asvgf-stable-antilag with the held history choice of two-history-hysteresis",
         .family = F::TwoHistory,
         .twoHistory = true,
         .asvgfGradient = true,
         .antilag = true,
         .stabilize = true,
         .stabilizeAntilag = true,
         .hystereticChoice = true,
         .needsGradientSamples = true,
         .needsSampleCount = true},
        {.name = "rae",
         .summary = "recurrent denoising autoencoder (Chaitanya 2017), denoise.rae.weights",
         .family = F::Rae},
        {.name = "rae-spp",
         .summary = "rae with the per-pixel sample count as an 8th input, denoise.rae.weights_spp",
         .family = F::Rae,
         .raeSampleCount = true},
    };
    return rows;
}

namespace {

// Splits "<base>+<demodulation>"; false when `name` has no (known) suffix.
bool SplitSuffix(std::string_view name, std::string_view& base, Demodulation& d) {
    const size_t plus = name.rfind('+');
    if (plus == std::string_view::npos || !ParseDemodulation(name.substr(plus + 1), d)) return false;
    base = name.substr(0, plus);
    return true;
}

}  // namespace

std::optional<Demodulation> DenoiserDemodulation(std::string_view name) {
    std::string_view base;
    Demodulation d;
    if (!SplitSuffix(name, base, d)) return std::nullopt;
    return d;
}

std::string_view DenoiserBaseName(std::string_view name) {
    std::string_view base;
    Demodulation d;
    return SplitSuffix(name, base, d) ? base : name;
}

const DenoiserVariant* LookupDenoiserVariant(std::string_view name) {
    const std::string_view base = DenoiserBaseName(name);
    for (const DenoiserVariant& v : DenoiserVariants())
        if (v.name == base) return &v;
    return nullptr;
}


namespace {

std::string UnknownDenoiserMessage(std::string_view name) {
    return fmt::format("unknown denoiser '{}' (did you mean '{}'? known: {}; each also as <name>+brdf or "
                       "<name>+albedo)",
                       name, NearestName(DenoiserBaseName(name), DenoiserNames()), fmt::join(DenoiserNames(), ", "));
}

}  // namespace

std::optional<std::string> DenoiserNameProblem(std::string_view name) {
    const DenoiserVariant* v = LookupDenoiserVariant(name);
    if (!v) return UnknownDenoiserMessage(name);
    // The network's weights were trained on albedo-demodulated illumination (Chaitanya et al. 2017,
    // §3.2); F_β input would need weights trained on it.
    if (v->family == DenoiserFamily::Rae && DenoiserDemodulation(name) == Demodulation::Brdf)
        return fmt::format("'{}': the RAE's weights were trained on albedo-demodulated illumination; use '{}' "
                           "(it re-divides an F_β-demodulated frame by the albedo itself)",
                           name, v->name);
    return std::nullopt;
}

const DenoiserVariant& FindDenoiserVariant(std::string_view name, std::string_view what) {
    if (std::optional<std::string> problem = DenoiserNameProblem(name)) Fail("{}: {}", what, *problem);
    return *LookupDenoiserVariant(name);
}

bool AcceptsZeroSamplePixels(const DenoiserVariant& variant) { return variant.family != DenoiserFamily::Rae; }

std::optional<std::string> ZeroSamplePixelsProblem(std::string_view name, std::string_view zeroSppKey) {
    const DenoiserVariant* v = LookupDenoiserVariant(name);
    if (!v || AcceptsZeroSamplePixels(*v)) return std::nullopt;
    return fmt::format("{} cannot take pixels without a path sample (its network has no notion of an empty "
                       "pixel and would see them black), and {} puts them in the spp map (raise it to 1, or "
                       "use an SVGF-family denoiser)",
                       name, zeroSppKey);
}

RendererNeeds RendererNeedsOf(const std::vector<std::string>& names, std::string_view what) {
    RendererNeeds needs;
    for (const std::string& name : names) {
        needs.gradientSamples |= FindDenoiserVariant(name, what).needsGradientSamples;
        needs.fbetaPlane |= DenoiserDemodulation(name) == Demodulation::Brdf;
    }
    return needs;
}

namespace {

struct MechanismName {
    bool DenoiserVariant::*flag;
    std::string_view name;
};
// One row per mechanism flag of DenoiserVariant, in the order a frame runs them.
constexpr MechanismName kMechanismNames[] = {
    {&DenoiserVariant::weightBySampleCount, "temporal weights x sample count (svgf-weighted)"},
    {&DenoiserVariant::asvgfGradient, "A-SVGF temporal gradient -> per-pixel alpha (Schied 2018)"},
    {&DenoiserVariant::antilag, "anti-lag: lambda shortens the history (Q2RTX)"},
    {&DenoiserVariant::suppressFireflies, "firefly suppression before accumulation"},
    {&DenoiserVariant::twoHistory, "second, sample-count-weighted history and the variance-optimal blend (Tu 2024)"},
    {&DenoiserVariant::emaGradient, "EMA luminance gradient -> q (Tu 2024)"},
    {&DenoiserVariant::hystereticChoice, "held history choice (band and rate)"},
    {&DenoiserVariant::clampHistory, "history clamp to the weighted history's neighbourhood"},
    {&DenoiserVariant::stabilize, "luminance stabilisation pass"},
    {&DenoiserVariant::stabilizeAntilag, "stabilisation weight driven by the change detector"},
    {&DenoiserVariant::raeSampleCount, "sample count as an extra network input"},
};

}  // namespace

std::string_view DenoiserFamilyName(DenoiserFamily family) {
    switch (family) {
        case DenoiserFamily::Svgf: return "svgf";
        case DenoiserFamily::TwoHistory: return "two-history";
        case DenoiserFamily::Rae: return "rae";
    }
    return "";
}

std::vector<std::string> VariantMechanisms(const DenoiserVariant& variant) {
    std::vector<std::string> names;
    for (const MechanismName& m : kMechanismNames)
        if (variant.*m.flag) names.emplace_back(m.name);
    return names;
}

std::vector<std::string> VariantRendererNeeds(const DenoiserVariant& variant) {
    std::vector<std::string> needs;
    if (variant.needsGradientSamples) needs.emplace_back("A-SVGF gradient samples (forward-projected, re-shaded)");
    if (variant.needsSampleCount)
        needs.emplace_back("per-pixel sample counts");
    else if (AcceptsZeroSamplePixels(variant))
        needs.emplace_back("per-pixel sample counts where the spp map may hold zeros (a foveation below 1 spp)");
    return needs;
}

const std::vector<std::string>& DenoiserNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const DenoiserVariant& v : DenoiserVariants()) n.emplace_back(v.name);
        return n;
    }();
    return names;
}

DenoiserParams ParamsForVariant(const DenoiserVariant& variant, DenoiserParams params) {
    params.svgf.weightBySampleCount = variant.weightBySampleCount;
    if (variant.raeSampleCount) params.rae.weights = params.rae.weightsSpp;
    return params;
}

std::vector<std::string> SvgfChannels(const SvgfParams& params) {
    std::vector<std::string> names;
    for (Channel ch : FilteredChannels(params)) names.emplace_back(ChannelName(ch));
    return names;
}

}  // namespace fovrt
