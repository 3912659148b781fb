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

std::vector<uint32_t> Results::Seeds(const std::string& scene) const {
    std::vector<uint32_t> out;
    for (const ResultRow& r : rows_)
        if (r.scene == scene && std::find(out.begin(), out.end(), r.seed) == out.end()) out.push_back(r.seed);
    return out;
}

std::string BaselineOf(const Results& results, const std::string& scene, const std::string& requested) {
    const std::vector<std::string> variants = results.Variants(scene);
    if (std::find(variants.begin(), variants.end(), requested) != variants.end()) return requested;
    return variants.empty() ? std::string() : variants.front();
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
    std::string out = "seed,frame,eye,variant,region,metric,value\n";
    for (const ResultRow& r : results.rows())
        if (r.scene == scene)
            out += fmt::format("{},{},{},{},{},{},{}\n", r.seed, r.frame, r.eye, CsvField(r.variant),
                               CsvField(r.region), CsvField(r.metric), FormatValue(r.value));
    return out;
}

void WriteFrameCsv(const std::filesystem::path& path, const Results& results, const std::string& scene) {
    WriteTextAtomically(path, FrameCsv(results, scene));
}

}  // namespace fovrt
