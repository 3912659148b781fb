// Tunables of the denoisers. Defaults are the struct initialisers below; key, range and meaning of
// each member are one row of its struct's table (params.cpp; rows: core/setting_table.h). The config reader and writer, the
// denoisers' checks and `fovrt config --keys` all walk those tables, so a parameter is added in
// two places: its member here and its row there.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <variant>

#include "core/setting_table.h"

namespace fovrt {

// Storage of the histories, the illumination ping-pong, the inputs. Auto is a setting, never a
// denoiser's: CreateDenoiser resolves it against the device (ResolvePrecision, denoiser_factory.h).
enum class Precision { Fp32, Fp16, Auto };

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
    bool weightBySampleCount = false;  // no setting: svgf-weighted's `weighted` mechanism (ParamsForVariant)
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
    float fireflySigma = 3.0f;     // k of the firefly variants' clamp μ + kσ
    float clampSigma = 0.5f;       // k of the clamp variants' box: I_w's 3×3 mean ± kσ
    float choiceRate = 0.25f;      // hysteresis variants: rate at which the held choice follows p
    float choiceBand = 0.3f;       // hysteresis variants: changes of p within ± band are held
    // The weighted history's window (denoise/history_window.h): the fraction of the image's width
    // and height where I_w, W_w and S_k are kept, centred on the gaze; 1 keeps them everywhere.
    float window = 1.0f;
};

// two-history-stable's stabilisation pass (denoise/two_history_stable.md): the stabilised
// luminance L_s ← lerp(clamp(L_s,prev, m ± k·σ), L, max(α_s, 1/W_u)) per channel, with m and σ²
// the 3×3 mean and spread of the filtered luminance plus its variance estimate.
struct TwoHistoryStableParams {
    float alpha = 0.2f;       // α_s: weight of this frame's luminance
    float sigmaScale = 1.0f;  // k: history clamp half-width in standard deviations
    float antilagQ = 0.2f;    // two-history-stable-antilag: q above which the weight rises to 1
};

// The recurrent denoising autoencoder (Chaitanya et al. 2017): which trained network to run. A
// path from a config file or --set arrives absolute (the config reader resolves it); a relative
// one (the defaults) is looked up in the working directory, then in the source tree (the
// committed weights).
struct RaeParams {
    std::string weights = "training/weights/rae-quarter.raew";           // variant rae
    std::string weightsSpp = "training/weights/rae-quarter-spp.raew";    // variant rae-spp
    // No setting: the variant's `balance` mechanism sets it (ParamsForVariant, RaeBalanceGains).
    bool balance = false;
};

struct DenoiserParams {
    SvgfParams svgf;
    AsvgfParams asvgf;
    TwoHistoryParams twoHistory;
    TwoHistoryStableParams twoHistoryStable;
    RaeParams rae;
    Precision precision = Precision::Fp32;
    // The spp map may hold 0 (a density below 1: docs/algorithms.md, "Pixels with zero path
    // samples"): the variants that read no sample count otherwise (svgf, asvgf, asvgf-antilag)
    // upload and read it so that a pixel without a path sample keeps its history, as the
    // count-weighted variants always do. Not a config key: a run derives it from its foveation
    // (RunDenoiseConfig, pipeline/denoiser_set.h), the live preview sets it. Off: no plane more.
    bool sampleCountsMayBeZero = false;
    // Room of the host-visible ring a frame's uploads and downloads stream through
    // (vk/transfer_ring.h): a frame whose transfers exceed it is submitted in parts. Not a config
    // key: it trades submits for memory only; tests shrink it to stream small frames.
    size_t transferRingBytes = size_t(16) << 20;
};

// ---- Parameter tables -------------------------------------------------------------------------

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
std::span<const SettingRow<RaeParams>> RaeParamTable();            // [denoise.rae]: weight files

// The precision enum's table: the names the key denoise.precision takes.
inline constexpr const char* kPrecisionKey = "denoise.precision";
inline constexpr const char* kPrecisionDoc = "storage of histories, illumination and inputs";
struct PrecisionRow {
    Precision value;
    const char* name;
    const char* doc;
};
std::span<const PrecisionRow> PrecisionTable();
NameList PrecisionNames();  // the table's names, in order
inline constexpr ParamInfo kPrecisionInfo{.key = kPrecisionKey, .doc = kPrecisionDoc, .names = PrecisionNames};
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

// Every key of the denoise tables a denoiser reads (the numeric ones of ForEachDenoiserParam, then
// the RAE's weights), in table order; denoise.precision and denoise.device are not among them.
std::vector<std::string> DenoiserSettingKeys();

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
