// Tunables of the denoisers. Defaults are the struct initialisers below; key, range and meaning of
// each member are one row of its struct's table (params.cpp). The config reader and writer, the
// denoisers' checks and `fovrt config --keys` all walk those tables, so a parameter is added in
// two places: its member here and its row there.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <variant>

namespace fovrt {

enum class Precision { Fp32, Fp16 };  // storage of history buffers

struct SvgfParams {
    float alphaColor = 0.2f;      // paper 0.2
    float alphaMoments = 0.2f;    // paper 0.2
    int atrousIterations = 5;     // paper 5
    int feedbackIteration = 1;    // paper 1, Falcor 2
    float sigmaDepth = 1.0f;      // σz
    float sigmaNormal = 128.0f;   // σn
    float sigmaLuminance = 4.0f;  // σl
    int varianceHistoryThreshold = 4;
    bool filterCombined = false;
    bool weightBySampleCount = false;
};

struct AsvgfParams {
    float alpha = 0.1f;            // paper 0.1
    int gradientIterations = 5;
    float antilagGain = 1.0f;      // anti-lag variants: a = clamp(gain·λ, 0, 1) (Q2RTX flt_antilag_hf 1)
    float antilagPower = 10.0f;    // anti-lag variants: history length × (1 − a)^power (Q2RTX 10)
};

struct TwoHistoryParams {
    float gradientBeta = 0.8f;     // β_g
    float qScale = 1.0f;           // S
};

// two-history-stable's stabilisation pass (denoise/two_history_stable.md): the stabilised
// luminance L_s ← lerp(clamp(L_s,prev, m ± k·σ), L, max(α_s, 1/W_u)) per channel, with m and σ²
// the 3×3 mean and spread of the filtered luminance plus its variance estimate.
struct TwoHistoryStableParams {
    float alpha = 0.2f;       // α_s: weight of this frame's luminance
    float sigmaScale = 1.0f;  // k: history clamp half-width in standard deviations
};

// The recurrent denoising autoencoder (SPEC §12): which trained network to run. A relative path
// is looked up in the working directory, then in the source tree (the committed weights).
inline constexpr const char* kRaeWeightsKey = "denoise.rae.weights";
inline constexpr const char* kRaeWeightsDoc = "RAE network weights (.raew, training/rae_net.py)";
inline constexpr const char* kRaeWeightsSppKey = "denoise.rae.weights_spp";
struct RaeParams {
    std::string weights = "training/weights/rae-quarter.raew";           // variant rae
    std::string weightsSpp = "training/weights/rae-quarter-spp.raew";    // variant rae-spp
};

struct DenoiserParams {
    SvgfParams svgf;
    AsvgfParams asvgf;
    TwoHistoryParams twoHistory;
    TwoHistoryStableParams twoHistoryStable;
    RaeParams rae;
    Precision precision = Precision::Fp32;
};

// ---- Parameter tables -------------------------------------------------------------------------

// Allowed values of a number; an open end excludes its bound.
struct ParamRange {
    double min = 0.0;
    double max = 0.0;
    bool minOpen = false;
    bool maxOpen = false;

    bool Contains(double value) const;  // false for NaN and infinities
    std::string Describe() const;       // "(0, 1]"
};

// What a row says about its parameter, whatever struct holds it.
struct ParamInfo {
    const char* key;   // full TOML key: "denoise.svgf.alpha_color"
    ParamRange range;  // unused for bool members
    const char* doc;   // one line
};

// One row of a struct's table: the info and the member it describes.
template <class Struct>
struct ParamRow {
    ParamInfo info;
    std::variant<float Struct::*, int Struct::*, bool Struct::*> member;
};

std::span<const ParamRow<SvgfParams>> SvgfParamTable();            // [denoise.svgf]
std::span<const ParamRow<AsvgfParams>> AsvgfParamTable();          // [denoise.asvgf]
std::span<const ParamRow<TwoHistoryParams>> TwoHistoryParamTable();  // [denoise.two_history]
std::span<const ParamRow<TwoHistoryStableParams>> TwoHistoryStableParamTable();  // [denoise.two_history_stable]

// The precision enum's table: the names the key denoise.precision takes.
inline constexpr const char* kPrecisionKey = "denoise.precision";
inline constexpr const char* kPrecisionDoc = "storage of history buffers";
struct PrecisionRow {
    Precision value;
    const char* name;
    const char* doc;
};
std::span<const PrecisionRow> PrecisionTable();
const char* PrecisionName(Precision precision);
// False when `name` is none of the table's names.
bool PrecisionFromName(const std::string& name, Precision& precision);
// The precision a command-line or config value names; fovrt::Error naming `what` (e.g.
// "--precision") and the valid names otherwise.
Precision ParsePrecision(const std::string& name, const std::string& what);

// Calls visit(info, value) for every row of every table, in table order ([denoise.svgf],
// [denoise.asvgf], [denoise.two_history], [denoise.two_history_stable]); `value` is the member inside `params` (float&, int& or
// bool&; const when `params` is).
template <class Params, class Visit>
void ForEachDenoiserParam(Params& params, Visit&& visit) {
    auto walk = [&](auto& section, auto table) {
        for (const auto& row : table)
            std::visit([&](auto member) { visit(row.info, section.*member); }, row.member);
    };
    walk(params.svgf, SvgfParamTable());
    walk(params.asvgf, AsvgfParamTable());
    walk(params.twoHistory, TwoHistoryParamTable());
    walk(params.twoHistoryStable, TwoHistoryStableParamTable());
}

// What is wrong with a table row (no key, no doc, min > max, an empty open range), or nullptr.
// params.cpp static_asserts it over every row; tests feed it bad rows.
constexpr const char* ParamRowProblem(const ParamInfo& info) {
    if (info.key == nullptr || info.key[0] == '\0') return "row without a key";
    if (info.doc == nullptr || info.doc[0] == '\0') return "row without a doc line";
    if (info.range.min > info.range.max) return "range with min > max";
    if (info.range.min == info.range.max && (info.range.minOpen || info.range.maxOpen))
        return "open range with min == max (empty)";
    return nullptr;
}

// A value that breaks a rule: the key to blame and why ("9 is out of range [0, 8]").
struct ParamProblem {
    std::string key;
    std::string message;
};
// The rule between keys: feedback_iteration <= atrous_iterations. For readers that report with
// their own context (the config reader adds file:line).
std::optional<ParamProblem> DenoiserParamConflict(const DenoiserParams& params);

// Every value within its row's range; fovrt::Error "<key>: <value> is out of range <range>"
// otherwise. The denoisers check this much: they also run feedback_iteration > atrous_iterations
// (as "no à-trous feedback"), which tests with zero iterations rely on.
void ValidateDenoiserParamRanges(const DenoiserParams& params);
// The ranges and the rule between keys (what a config must satisfy).
void ValidateDenoiserParams(const DenoiserParams& params);

}  // namespace fovrt
