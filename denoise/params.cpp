#include "denoise/params.h"

#include <array>

#include "core/error.h"
#include "shaders/shared_constants.h"

namespace fovrt {
namespace {

constexpr ParamRange kAnyBool{};
// Iteration counts share the shaders' cap (timestamp pools and step tables are sized by it).
constexpr ParamRange kIterations = Closed(0, FOVRT_MAX_ATROUS_ITERATIONS);

using S = SvgfParams;
constexpr std::array<ParamRow<SvgfParams>, 9> kSvgfRows{{
    {{"denoise.svgf.alpha_color", OpenMin(0, 1), "temporal EMA weight of new colour (paper 0.2)"},
     &S::alphaColor},
    {{"denoise.svgf.alpha_moments", OpenMin(0, 1), "temporal EMA weight of new moments (paper 0.2)"},
     &S::alphaMoments},
    {{"denoise.svgf.atrous_iterations", kIterations, "à-trous wavelet iterations (paper 5)"},
     &S::atrousIterations},
    {{"denoise.svgf.feedback_iteration", kIterations,
      "à-trous iteration (1-based) fed back as colour history; 0 = unfiltered (paper 1, Falcor 2)"},
     &S::feedbackIteration},
    {{"denoise.svgf.sigma_depth", OpenMin(0, 1e6), "depth edge-stopping σz"}, &S::sigmaDepth},
    {{"denoise.svgf.sigma_normal", Closed(0, 1e6), "normal edge-stopping exponent σn"}, &S::sigmaNormal},
    {{"denoise.svgf.sigma_luminance", OpenMin(0, 1e6), "luminance edge-stopping σl"},
     &S::sigmaLuminance},
    {{"denoise.svgf.variance_history_threshold", Closed(0, 1 << 20),
      "history length below which variance is estimated spatially (7×7)"},
     &S::varianceHistoryThreshold},
    {{"denoise.svgf.filter_combined", kAnyBool, "filter direct+indirect together instead of separately"},
     &S::filterCombined},
    // weightBySampleCount is no setting: the variant's `weighted` mechanism sets it (ParamsForVariant).
}};

constexpr std::array<ParamRow<AsvgfParams>, 4> kAsvgfRows{{
    {{"denoise.asvgf.alpha", OpenMin(0, 1),
      "base temporal weight α of asvgf, two-history-asvgf (paper 0.1); the anti-lag variants use SVGF's"},
     &AsvgfParams::alpha},
    {{"denoise.asvgf.gradient_iterations", kIterations, "à-trous iterations at stratum resolution"},
     &AsvgfParams::gradientIterations},
    // The anti-lag variants' (asvgf-antilag, two-history-asvgf-antilag) reaction to λ.
    {{"denoise.asvgf.antilag_gain", Closed(0, 64),
      "anti-lag strength: a = clamp(gain·λ, 0, 1); 0 = SVGF (Q2RTX 1)"},
     &AsvgfParams::antilagGain},
    {{"denoise.asvgf.antilag_power", Closed(0, 64),
      "anti-lag history reduction: length × (1 − a)^power; 0 keeps the length (Q2RTX 10)"},
     &AsvgfParams::antilagPower},
}};

// firefly_sigma: 0 clamps a sample to max(history mean, brightest neighbour); 3 leaves a Gaussian's
// samples alone 99.9 % of the time; large values switch the suppression off.
// clamp_sigma: 0 clamps I_u to the segment between I_w's 3×3 mean and I_w; large values keep I_u
// (the blend then follows q alone).
// choice_rate 1 with choice_band 0 is two-history's p; a small rate spreads a flip of p over
// ~1/rate frames, and a band holds p against its frame-to-frame jitter.
// window: the weighted history kept in a gaze-following window (Tu 2024's future work: its extra
// memory); outside it the blend takes the unweighted history (SVGF's path).
constexpr std::array<ParamRow<TwoHistoryParams>, 7> kTwoHistoryRows{{
    {{"denoise.two_history.gradient_beta", Closed(0, 1), "β_g of the gradient EMA"},
     &TwoHistoryParams::gradientBeta},
    {{"denoise.two_history.q_scale", Closed(0, 1e6), "S in q = clamp(S·|lum g| / std(lum I_u), 0, 1)"},
     &TwoHistoryParams::qScale},
    {{"denoise.two_history.firefly_sigma", Closed(0, 1e6),
      "k: the firefly variants clamp a sample above mu + k sigma of its moments history and above its 8 neighbours"},
     &TwoHistoryParams::fireflySigma},
    {{"denoise.two_history.clamp_sigma", Closed(0, 1e6),
      "k: the clamp variants keep I_u inside I_w's 3x3 mean +- k sigma (widened to hold I_w) instead of the choice p"},
     &TwoHistoryParams::clampSigma},
    {{"denoise.two_history.choice_rate", OpenMin(0, 1),
      "r: the hysteresis variants' held choice moves by r times p's excess over the band each frame"},
     &TwoHistoryParams::choiceRate},
    {{"denoise.two_history.choice_band", Closed(0, 1),
      "h: the hysteresis variants hold their choice while p stays within +- h of it"},
     &TwoHistoryParams::choiceBand},
    {{"denoise.two_history.window", OpenMin(0, 1),
      "fraction of the image's width and height, centred on the gaze, where the weighted history is kept (1: all)"},
     &TwoHistoryParams::window},
}};

// Ranges: α_s = 1 passes the filtered frame through (no stabilisation); small α_s averages over
// ~1/α_s frames. k = 0 pins the history to the neighbourhood mean; large k (≥ 4) leaves it
// unclamped wherever the variance estimate is honest. antilag_q: q of a static view's noise stays
// below ~0.5 (denoise/two_history_stable.md), a change drives it to 1.
constexpr std::array<ParamRow<TwoHistoryStableParams>, 3> kTwoHistoryStableRows{{
    {{"denoise.two_history_stable.alpha", OpenMin(0, 1),
      "stabilisation weight alpha_s of this frame's luminance (two-history-stable)"},
     &TwoHistoryStableParams::alpha},
    {{"denoise.two_history_stable.sigma_scale", Closed(0, 1e6),
      "k: stabilised history clamped to the 3x3 mean +- k sigma (two-history-stable)"},
     &TwoHistoryStableParams::sigmaScale},
    {{"denoise.two_history_stable.antilag_q", OpenMax(0, 1),
      "q0: two-history-stable-antilag raises alpha_s to (q - q0)/(1 - q0) where q > q0"},
     &TwoHistoryStableParams::antilagQ},
}};

constexpr std::array<SettingRow<RaeParams>, 2> kRaeRows{{
    {{.key = "denoise.rae.weights", .doc = "RAE network weights (.raew, training/rae_net.py), variant rae",
      .nonEmpty = true, .path = true},
     &RaeParams::weights},
    {{.key = "denoise.rae.weights_spp", .doc = "RAE network weights of variant rae-spp", .nonEmpty = true,
      .path = true},
     &RaeParams::weightsSpp},
}};

constexpr std::array<PrecisionRow, 3> kPrecisionRows{{
    {Precision::Fp32, "fp32", "32-bit float histories"},
    {Precision::Fp16, "fp16", "16-bit histories, filtered illumination and inputs (octahedral normals)"},
    {Precision::Auto, "auto", "fp16 for the SVGF family on a GPU with 16-bit storage; fp32 on a CPU device, "
                              "for the C++ reference and for the RAE"},
}};

constexpr std::array<const char*, kPrecisionRows.size()> kPrecisionNames = [] {
    std::array<const char*, kPrecisionRows.size()> names{};
    for (size_t i = 0; i < kPrecisionRows.size(); ++i) names[i] = kPrecisionRows[i].name;
    return names;
}();

static_assert(RowsWellFormed(kSvgfRows) && RowsWellFormed(kAsvgfRows) && RowsWellFormed(kTwoHistoryRows) &&
                  RowsWellFormed(kTwoHistoryStableRows) && RowsWellFormed(kRaeRows),
              "a parameter row lacks a key or doc, or has an empty range (see ParamRowProblem)");

}  // namespace

std::span<const ParamRow<SvgfParams>> SvgfParamTable() { return kSvgfRows; }

std::vector<std::string> DenoiserSettingKeys() {
    std::vector<std::string> keys;
    const DenoiserParams defaults;
    ForEachDenoiserParam(defaults, [&](const ParamInfo& info, const auto&) { keys.emplace_back(info.key); });
    for (const auto& row : kRaeRows) keys.emplace_back(row.info.key);
    return keys;
}
std::span<const ParamRow<AsvgfParams>> AsvgfParamTable() { return kAsvgfRows; }
std::span<const ParamRow<TwoHistoryParams>> TwoHistoryParamTable() { return kTwoHistoryRows; }
std::span<const ParamRow<TwoHistoryStableParams>> TwoHistoryStableParamTable() { return kTwoHistoryStableRows; }
std::span<const SettingRow<RaeParams>> RaeParamTable() { return kRaeRows; }
std::span<const PrecisionRow> PrecisionTable() { return kPrecisionRows; }
NameList PrecisionNames() { return kPrecisionNames; }

const char* PrecisionName(Precision precision) {
    for (const PrecisionRow& row : kPrecisionRows)
        if (row.value == precision) return row.name;
    return "?";
}

bool PrecisionFromName(const std::string& name, Precision& precision) {
    for (const PrecisionRow& row : kPrecisionRows)
        if (name == row.name) {
            precision = row.value;
            return true;
        }
    return false;
}

Precision ParsePrecision(const std::string& name, const std::string& what) {
    Precision precision = Precision::Fp32;
    if (PrecisionFromName(name, precision)) return precision;
    std::string names;
    for (const PrecisionRow& row : kPrecisionRows) names += std::string(names.empty() ? "" : " or ") + row.name;
    Fail("{} '{}': expected {}", what, name, names);
}

std::optional<ParamProblem> DenoiserParamConflict(const DenoiserParams& params) {
    const SvgfParams& s = params.svgf;
    if (s.feedbackIteration > s.atrousIterations)
        return ParamProblem{"denoise.svgf.feedback_iteration",
                            fmt::format("{} must be <= denoise.svgf.atrous_iterations = {}",
                                        s.feedbackIteration, s.atrousIterations)};
    return std::nullopt;
}

void ValidateDenoiserParamRanges(const DenoiserParams& params) {
    ValidateRows(params.svgf, SvgfParamTable());
    ValidateRows(params.asvgf, AsvgfParamTable());
    ValidateRows(params.twoHistory, TwoHistoryParamTable());
    ValidateRows(params.twoHistoryStable, TwoHistoryStableParamTable());
}

void ValidateDenoiserParams(const DenoiserParams& params) {
    ValidateDenoiserParamRanges(params);
    ValidateRows(params.rae, RaeParamTable());
    if (std::optional<ParamProblem> problem = DenoiserParamConflict(params))
        Fail("{}: {}", problem->key, problem->message);
}

}  // namespace fovrt
