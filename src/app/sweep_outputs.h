// The outputs of a sampling-design sweep (app/design_sweep.h), from every point's results:
//   curves.csv     one row per (scene, variant, design, budget, seed): the measured traced path
//                  samples per pixel (whole, fovea, periphery), JOD and its two channels, whole and
//                  foveal relMSE, foveal flicker: the rate–quality curves' data
//   summary.json   per design its keys and per point the measured sampling and the means; per
//                  (scene, variant, design) the rays saved at equal JOD against the anchor design
//                  and the JOD gain at equal rays, each with its seed-bootstrap interval
//                  (metrics/rate_quality.h), and per point the rays saved at its own JOD
//   report.html    the headline table, then JOD against rays per (scene, variant), one curve per
//                  design, the rays saved at each point against rays, and the points table; each point's own report is in designs/<point>/
//   manifest.json  the sweep (designs, budgets, anchor, points), scenes, variants, seeds, build, time
// and the headline table on stdout.
#pragma once

#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/experiment.h"
#include "app/experiment_vdp.h"
#include "app/report_html.h"
#include "metrics/rate_quality.h"

namespace fovrt {

// curves.csv's columns, in order.
inline constexpr const char* kCurvesCsvHeader =
    "scene,variant,design,budget_spp,seed,traced_spp_whole,traced_spp_fovea,traced_spp_periphery,guide_rays_whole,jod,"
    "jod_sustained,jod_transient,relmse_whole,relmse_fovea,flicker_fovea";

// What the sweep keeps of one point.
struct SweepPointResult {
    size_t point = 0;                                          // index into SamplingSweep::points
    std::vector<std::string> scenes;                           // scene labels, in experiment order
    std::map<std::string, std::array<double, 3>> tracedSpp;    // label -> whole, fovea, periphery
    std::map<std::string, double> guideRays;                   // label -> guide rays per pixel, whole image
    Results results;
    std::vector<VdpScore> vdp;
};

// One (scene, variant) at one point, per run seed (the experiment's seeds, in order).
struct SweepPointValues {
    std::array<double, 3> tracedSpp{};  // measured over every seed: whole, fovea, periphery
    double guideRays = 0.0;             // guide rays per pixel (pixels without a path sample), whole image
    std::vector<double> jod, jodSustained, jodTransient;  // mean over the eyes
    std::vector<double> relmseWhole, relmseFovea, flickerFovea;  // mean over frames and eyes
};
SweepPointValues PointValues(const SweepPointResult& point, const std::string& scene, const std::string& variant,
                             const std::vector<uint32_t>& seeds);

// A design's curve against the anchor's for one (scene, variant).
struct RaysSavedRow {
    std::string scene, variant, design;
    BjontegaardInterval raysSaved;  // anchor rays / design rays at equal JOD
    BjontegaardInterval jodGain;    // design JOD − anchor JOD at equal rays
    // anchor rays / design rays at equal foveal relMSE (the fit's quality: −ln relMSE, so the seeds
    // average as a geometric mean): what the rays buy where the eye looks, which the whole-image
    // JOD can outweigh with the periphery.
    BjontegaardInterval raysSavedFovea;
    // At each of the design's points (budgets ascending): uniform's rays for that point's JOD over
    // its own, where its JOD lies within the anchor's range: how the saving changes with the budget.
    std::vector<BjontegaardInterval> raysSavedAtPoints;
};
// The quality the foveal curves fit: −ln foveal relMSE, higher is better, and its seed mean is the
// log of the geometric mean.
inline double FovealQuality(double fovealRelMse) { return -std::log(fovealRelMse); }

// A design's curves against the anchor's on one (scene, variant): JOD against rays, and −ln foveal
// relMSE against rays (per seed; the seed mean is the log of the geometric mean).
RaysSavedRow CompareCurves(std::string scene, std::string variant, std::string design, const SeededRateQualityCurve& anchor,
                           const SeededRateQualityCurve& anchorFovea, const SeededRateQualityCurve& test,
                           const SeededRateQualityCurve& testFovea);
// Every design but the anchor against the anchor, per scene and variant (none without an anchor
// or with fewer than two budgets).
std::vector<RaysSavedRow> SweepRaysSaved(const ExperimentSpec& spec, const std::vector<SweepPointResult>& points);

// The headline table as text against the anchor design `anchor` (empty: the sweep has none): scene,
// variant, design, rays saved and JOD gain with intervals.
// `unit`: what the bootstrap resamples ("seed", or "window and seed" over pooled gaze windows).
std::string RaysSavedTable(const std::string& anchor, const std::vector<RaysSavedRow>& rows,
                           const std::string& unit = "seed");
// How rays saved, JOD gain and their intervals are measured, as summary.json and `fovrt rays-saved
// --json` state it.
inline constexpr const char* kRaysSavedMethod =
    "rays = measured traced path samples per pixel (whole image, every eye-frame); JOD = FovVideoVDP, mean "
    "over eyes per seed; rays saved = anchor rays / design rays at equal JOD (Bjøntegaard delta on PCHIP "
    "fits of ln rays over JOD, over the JOD range both curves cover); JOD gain = design − anchor at equal "
    "rays; rays saved fovea = the same on -ln foveal relMSE (geometric mean over seeds) instead of JOD; 95 % "
    "percentile intervals from a paired bootstrap over seeds (2000 resamples)";
// An interval as JSON, unrounded: {"value", "over": [from, to], "lower", "upper",
// "failed_resamples"}, or {"value": null, "reason"}; "interval_reason" where there is a value and
// no interval.
nlohmann::json IntervalJson(const BjontegaardInterval& interval);
// "2.00× [1.90, 2.10]" (`format` for each number, then `unit`), or the reason there is no value or
// no interval.
std::string IntervalText(const BjontegaardInterval& interval, const char* format, const char* unit);
// A table as aligned text, two spaces in, a line per row.
std::string TextTable(const ReportTable& table);

void WriteSweepOutputs(const ExperimentSpec& spec, const std::vector<SweepPointResult>& points,
                       const std::filesystem::path& outDir, std::chrono::steady_clock::time_point start);

}  // namespace fovrt
