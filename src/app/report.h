// Results of an experiment and their text outputs (SPEC §5, §8):
//   - Results: one row per (scene, frame, eye, variant, region, metric) value;
//   - per-frame CSV `frame,eye,variant,region,metric,value` (one file per scene);
//   - summary: means over frames and eyes per (scene, variant, region, metric), with % relative
//     to the baseline variant (`svgf`, the thesis's "Unweighted"), as JSON and as the stdout
//     table in the thesis layout (relMSE and SSIM, whole and fovea).
// Every output states the relMSE ε. The HTML report is in report_html.h.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fovrt {

inline constexpr const char* kBaselineVariant = "svgf";

struct ResultRow {
    std::string scene;
    int frame = 0;
    int eye = 0;
    std::string variant;
    std::string region;  // "whole", "fovea", "periphery", "ecc0-5", ...
    std::string metric;  // "relmse", "ssim", "flip", "temporal"
    double value = 0.0;
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

    std::optional<SummaryValue> Mean(const std::string& scene, const std::string& variant,
                                     const std::string& region, const std::string& metric) const;
    // Per frame, averaged over eyes: (frame, value), sorted by frame.
    std::vector<std::pair<int, double>> PerFrame(const std::string& scene, const std::string& variant,
                                                 const std::string& region, const std::string& metric) const;

private:
    std::vector<ResultRow> rows_;
};

// 100 (value − baseline) / baseline; nullopt when the baseline is 0 or missing.
std::optional<double> PercentRelative(double value, std::optional<double> baseline);
// "+1.234%" with `decimals` digits; values that round to zero print as "+0.000%" (no "-0.000%").
std::string FormatPercent(double percent, int decimals);

// CSV text of one scene: header `frame,eye,variant,region,metric,value`, rows in insertion order,
// values with 9 significant digits (identical runs give identical bytes).
std::string FrameCsv(const Results& results, const std::string& scene);
void WriteFrameCsv(const std::filesystem::path& path, const Results& results, const std::string& scene);

// {"relmse_epsilon", "baseline", "scenes": {scene: {"variants": {variant: {region: {metric:
// {"mean", "count", "percent_vs_baseline"}}}}}}}
nlohmann::json SummaryJson(const Results& results, const std::string& baseline = kBaselineVariant);
void WriteSummaryJson(const std::filesystem::path& path, const Results& results,
                      const std::string& baseline = kBaselineVariant);

// The thesis table: per scene, one row per variant with relMSE and SSIM (whole, fovea) and the
// same four as % relative to the baseline.
std::string SummaryTable(const Results& results, const std::string& baseline = kBaselineVariant);

}  // namespace fovrt
