#include "app/report.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <fmt/format.h>

#include "core/atomic_file.h"

namespace fovrt {

namespace {

void AppendUnique(std::vector<std::string>& list, const std::string& value) {
    if (std::find(list.begin(), list.end(), value) == list.end()) list.push_back(value);
}

std::string FormatValue(double v) {
    if (std::isnan(v)) return "nan";
    return fmt::format("{:.9g}", v);
}

// CSV fields are identifiers; quote anything that could break a row anyway.
std::string CsvField(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) {
        if (c == '"') out += '"';
        out += c;
    }
    return out + "\"";
}

}  // namespace

void Results::Add(ResultRow row) { rows_.push_back(std::move(row)); }

std::vector<std::string> Results::Scenes() const {
    std::vector<std::string> out;
    for (const ResultRow& r : rows_) AppendUnique(out, r.scene);
    return out;
}

std::vector<std::string> Results::Variants(const std::string& scene) const {
    std::vector<std::string> out;
    for (const ResultRow& r : rows_)
        if (r.scene == scene) AppendUnique(out, r.variant);
    return out;
}

std::vector<std::string> Results::Metrics(const std::string& scene) const {
    std::vector<std::string> out;
    for (const ResultRow& r : rows_)
        if (r.scene == scene) AppendUnique(out, r.metric);
    return out;
}

std::vector<std::string> Results::Regions(const std::string& scene) const {
    std::vector<std::string> out;
    for (const ResultRow& r : rows_)
        if (r.scene == scene) AppendUnique(out, r.region);
    return out;
}

std::optional<SummaryValue> Results::Mean(const std::string& scene, const std::string& variant,
                                          const std::string& region, const std::string& metric) const {
    double sum = 0;
    size_t count = 0;
    for (const ResultRow& r : rows_)
        if (r.scene == scene && r.variant == variant && r.region == region && r.metric == metric &&
            !std::isnan(r.value)) {
            sum += r.value;
            ++count;
        }
    if (count == 0) return std::nullopt;
    return SummaryValue{sum / double(count), count};
}

std::vector<std::pair<int, double>> Results::PerFrame(const std::string& scene, const std::string& variant,
                                                      const std::string& region,
                                                      const std::string& metric) const {
    std::map<int, std::pair<double, int>> byFrame;
    for (const ResultRow& r : rows_)
        if (r.scene == scene && r.variant == variant && r.region == region && r.metric == metric &&
            !std::isnan(r.value)) {
            auto& [sum, n] = byFrame[r.frame];
            sum += r.value;
            ++n;
        }
    std::vector<std::pair<int, double>> out;
    for (const auto& [frame, acc] : byFrame) out.emplace_back(frame, acc.first / acc.second);
    return out;
}

std::optional<double> PercentRelative(double value, std::optional<double> baseline) {
    if (!baseline || *baseline == 0.0 || std::isnan(*baseline)) return std::nullopt;
    return 100.0 * (value - *baseline) / *baseline;
}

std::string FormatPercent(double percent, int decimals) {
    if (std::abs(percent) < 0.5 * std::pow(10.0, -decimals)) percent = 0.0;
    return fmt::format("{:+.{}f}%", percent, decimals);
}

std::string FrameCsv(const Results& results, const std::string& scene) {
    std::string out = "frame,eye,variant,region,metric,value\n";
    for (const ResultRow& r : results.rows())
        if (r.scene == scene)
            out += fmt::format("{},{},{},{},{},{}\n", r.frame, r.eye, CsvField(r.variant), CsvField(r.region),
                               CsvField(r.metric), FormatValue(r.value));
    return out;
}

void WriteFrameCsv(const std::filesystem::path& path, const Results& results, const std::string& scene) {
    WriteTextAtomically(path, FrameCsv(results, scene));
}

nlohmann::json SummaryJson(const Results& results, const std::string& baseline) {
    nlohmann::json j;
    j["relmse_epsilon"] = results.relMseEpsilon;
    j["baseline"] = baseline;
    j["aggregation"] = "mean over frames and eyes";
    j["definitions"] = {
        {"relmse", "mean over pixels and RGB of (y-r)^2/(r^2+eps), HDR"},
        {"ssim", "Wang 2004, 11x11 Gaussian sigma 1.5, K1 0.01, K2 0.03, L 1, on the Rec.709 luma of "
                 "tonemapped values (clamp to [0,1], sRGB encode); window renormalised at borders"},
        {"flip", "LDR-FLIP (Andersson 2020) on the same tonemap at the eye's pixels per degree"},
        {"temporal", "mean |lum(out_t) - lum(out_t-1)| of the same variant, HDR Rec.709 luminance"},
        {"regions", "fovea: gaze-centred disc; periphery: complement; eccN-M: view-ray angle to gaze in [N,M) deg"}};
    nlohmann::json scenes = nlohmann::json::object();
    for (const std::string& scene : results.Scenes()) {
        nlohmann::json variants = nlohmann::json::object();
        for (const std::string& variant : results.Variants(scene)) {
            nlohmann::json regions = nlohmann::json::object();
            for (const std::string& region : results.Regions(scene)) {
                nlohmann::json metrics = nlohmann::json::object();
                for (const std::string& metric : results.Metrics(scene)) {
                    auto m = results.Mean(scene, variant, region, metric);
                    if (!m) continue;
                    nlohmann::json entry = {{"mean", m->mean}, {"count", m->count}};
                    auto base = results.Mean(scene, baseline, region, metric);
                    auto pct = PercentRelative(m->mean, base ? std::optional<double>(base->mean) : std::nullopt);
                    entry["percent_vs_baseline"] = pct ? nlohmann::json(*pct) : nlohmann::json(nullptr);
                    metrics[metric] = entry;
                }
                if (!metrics.empty()) regions[region] = metrics;
            }
            variants[variant] = regions;
        }
        scenes[scene] = {{"variants", variants}};
    }
    j["scenes"] = scenes;
    return j;
}

void WriteSummaryJson(const std::filesystem::path& path, const Results& results, const std::string& baseline) {
    WriteTextAtomically(path, SummaryJson(results, baseline).dump(2) + "\n");
}

std::string SummaryTable(const Results& results, const std::string& baseline) {
    std::string out;
    struct Column {
        const char* metric;
        const char* region;
        const char* label;
    };
    const Column columns[] = {{"relmse", "whole", "relMSE"},
                              {"relmse", "fovea", "relMSE fovea"},
                              {"ssim", "whole", "SSIM"},
                              {"ssim", "fovea", "SSIM fovea"}};
    for (const std::string& scene : results.Scenes()) {
        const bool hasBaseline = !results.Variants(scene).empty() &&
                                 std::ranges::count(results.Variants(scene), baseline) > 0;
        out += fmt::format("Scene {}  (mean over frames and eyes; relMSE eps = {:g}; % vs {})\n", scene,
                           results.relMseEpsilon, hasBaseline ? baseline : std::string("n/a"));
        out += fmt::format("{:<20}", "variant");
        for (const Column& c : columns) out += fmt::format(" {:>13}", c.label);
        for (const Column& c : columns) out += fmt::format(" {:>14}", fmt::format("%{}", c.label));
        out += "\n";
        for (const std::string& variant : results.Variants(scene)) {
            out += fmt::format("{:<20}", variant);
            for (const Column& c : columns) {
                auto m = results.Mean(scene, variant, c.region, c.metric);
                std::string cell = !m ? "-"
                                      : std::string(c.metric) == "relmse" ? fmt::format("{:.3e}", m->mean)
                                                                          : fmt::format("{:.4f}", m->mean);
                out += fmt::format(" {:>13}", cell);
            }
            for (const Column& c : columns) {
                auto m = results.Mean(scene, variant, c.region, c.metric);
                auto b = results.Mean(scene, baseline, c.region, c.metric);
                std::optional<double> pct;
                if (m && variant != baseline) pct = PercentRelative(m->mean, b ? std::optional<double>(b->mean) : std::nullopt);
                std::string cell = !pct ? "-" : FormatPercent(*pct, std::string(c.metric) == "relmse" ? 3 : 4);
                out += fmt::format(" {:>14}", cell);
            }
            out += "\n";
        }
        out += "\n";
    }
    return out;
}

}  // namespace fovrt
