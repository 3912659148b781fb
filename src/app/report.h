// Results of an experiment and their text outputs (SPEC §5, §8):
//   - Results: one row per (scene, seed, frame, eye, variant, region, metric) value;
//   - per-frame CSV `seed,frame,eye,variant,region,metric,value` (one file per scene): every value;
//   - summary (app/experiment_stats.h): per (scene, variant, region, metric) the mean, median and
//     geometric mean over frames, eyes and seeds, and against the baseline variant (the first, or
//     experiment.baseline) the paired per-frame ratio with its block-bootstrap interval and the
//     win rate, as JSON (`summary.json`) and as the stdout table (relMSE and temporal error side
//     by side per region, SSIM).
// Every output states the relMSE ε and the statistics method. The HTML report is in report_html.h.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fovrt {

struct ResultRow {
    std::string scene;
    int frame = 0;
    int eye = 0;
    std::string variant;
    std::string region;  // "whole", "fovea", "periphery", "ecc0-5", ...
    std::string metric;  // "relmse", "ssim", "flip", "temporal"
    double value = 0.0;
    uint32_t seed = 1;   // run.seed of the pass that rendered the frame
};

// Mean of one (scene, variant, region, metric) over frames and eyes.
struct SummaryValue {
    double mean = 0.0;
    size_t count = 0;
};

class Results {
public:
    double relMseEpsilon = 0.01;  // ε of relMSE, stated in every output

    void Add(ResultRow row);
    const std::vector<ResultRow>& rows() const { return rows_; }

    // Scenes and variants in first-seen order (the order of the experiment file).
    std::vector<std::string> Scenes() const;
    std::vector<std::string> Variants(const std::string& scene) const;
    std::vector<std::string> Metrics(const std::string& scene) const;
    std::vector<std::string> Regions(const std::string& scene) const;
    std::vector<uint32_t> Seeds(const std::string& scene) const;

    std::optional<SummaryValue> Mean(const std::string& scene, const std::string& variant,
                                     const std::string& region, const std::string& metric) const;
    // Per frame, averaged over eyes and seeds: (frame, value), sorted by frame.
    std::vector<std::pair<int, double>> PerFrame(const std::string& scene, const std::string& variant,
                                                 const std::string& region, const std::string& metric) const;

private:
    std::vector<ResultRow> rows_;
};

// 100 (value − baseline) / baseline; nullopt when the baseline is 0 or missing.
std::optional<double> PercentRelative(double value, std::optional<double> baseline);
// "+1.234%" with `decimals` digits; values that round to zero print as "+0.000%" (no "-0.000%").
std::string FormatPercent(double percent, int decimals);

// CSV text of one scene: header `seed,frame,eye,variant,region,metric,value`, rows in insertion order,
// values with 9 significant digits (identical runs give identical bytes).
std::string FrameCsv(const Results& results, const std::string& scene);
void WriteFrameCsv(const std::filesystem::path& path, const Results& results, const std::string& scene);

// The baseline of a scene: `requested` when that variant is in the scene, else the scene's first
// variant ("" when the scene has none).
std::string BaselineOf(const Results& results, const std::string& scene, const std::string& requested = "");

}  // namespace fovrt
