// The experiment summary as text: `summary.json` and the table printed on stdout, both from
// ExperimentStats (app/experiment_stats.h), both stating the statistics method.
//
// The stdout table, per scene: one row per variant × region (whole, fovea, periphery) with
//   relMSE mean, median, geometric mean | relMSE ratio to the baseline [95 % CI] (ns = the
//   interval contains 1) | win rate | temporal error mean | temporal ratio [95 % CI] | SSIM mean,
// then the frames that dominate a variant's mean relMSE, when a fifth of the frames or fewer
// hold half of it.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "app/experiment_stats.h"
#include "app/experiment_vdp.h"
#include "app/report.h"

namespace fovrt {

// "0.823 [0.791, 0.861]", with " ns" appended when the interval contains 1; more decimals (up to
// 5) when 3 would print a significant interval as touching 1 or a zero width; "-" without pairs.
std::string FormatRatio(const PairedRatio& ratio);

// {"relmse_epsilon", "method", "bootstrap", "definitions", "scenes": {scene: {"seeds", "frames",
// "eyes", "baseline", "variants": {variant: {region: {metric: {"mean", "median",
// "geometric_mean", "count", "percent_vs_baseline", "vs_baseline": {"ratio", "ci_low",
// "ci_high", "confidence", "significant", "win_rate", "pairs", "dropped", "block_length"},
// "dominant_frames": {"frames", "share"}}}}}}}}
nlohmann::json SummaryJson(const Results& results, const ExperimentStats& stats);
void WriteSummaryJson(const std::filesystem::path& path, const Results& results, const ExperimentStats& stats);

std::string SummaryTable(const Results& results, const ExperimentStats& stats);

// The report's per-seed table: per scene, seed and variant, that seed's means over frames and
// eyes of relMSE (whole, fovea, periphery), SSIM and FLIP (whole) and, where `vdp` scored it, the
// FovVideoVDP JOD (mean over eyes): how far each seed's figures lie from the pooled summary.
ReportTable PerSeedTable(const Results& results, const std::vector<VdpScore>& vdp);

}  // namespace fovrt
