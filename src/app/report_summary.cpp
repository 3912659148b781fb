#include "app/report_summary.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string_view>
#include <tuple>

#include <fmt/format.h>

#include "core/atomic_file.h"

namespace fovrt {

namespace {

std::string Sci(double v) { return std::isnan(v) ? "-" : fmt::format("{:.3e}", v); }

nlohmann::json Number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

std::string SeedList(const std::vector<uint32_t>& seeds) {
    std::string out;
    for (uint32_t s : seeds) out += (out.empty() ? "" : ", ") + std::to_string(s);
    return out;
}

}  // namespace

std::string FormatRatio(const PairedRatio& r) {
    if (r.pairs == 0) return "-";
    // 3 decimals, more (up to 5) while the printed interval would hide its width or its side of 1.
    auto rounded = [](double v, int d) { return std::round(v * std::pow(10.0, d)); };
    int d = 3;
    while (d < 5) {
        const double lo = rounded(r.lower, d), hi = rounded(r.upper, d), one = rounded(1.0, d);
        const bool hidesWidth = lo == hi && r.upper - r.lower > 1e-7 * r.upper;  // not a rounding difference
        const bool hidesSide = r.Significant() && lo <= one && one <= hi;
        if (!hidesWidth && !hidesSide) break;
        ++d;
    }
    return fmt::format("{:.{}f} [{:.{}f}, {:.{}f}]{}", r.ratio, d, r.lower, d, r.upper, d, r.Significant() ? "" : " ns");
}

nlohmann::json SummaryJson(const Results& results, const ExperimentStats& stats) {
    nlohmann::json j;
    j["relmse_epsilon"] = results.relMseEpsilon;
    j["aggregation"] = "mean, median and geometric mean over frames, eyes and seeds";
    j["method"] = StatisticsMethod(stats.Options());
    j["bootstrap"] = {{"kind", "circular moving-block"},
                      {"resamples", stats.Options().resamples},
                      {"confidence", stats.Options().confidence},
                      {"rng_seed", stats.Options().rngSeed},
                      {"block_length", "Politis & White (2004) from the autocorrelation, per comparison"}};
    j["definitions"] = {
        {"relmse", "mean over pixels and RGB of (y-r)^2/(r^2+eps), HDR"},
        {"ssim", "Wang 2004, 11x11 Gaussian sigma 1.5, K1 0.01, K2 0.03, L 1, on the Rec.709 luma of "
                 "tonemapped values (clamp to [0,1], sRGB encode); window renormalised at borders"},
        {"flip", "LDR-FLIP (Andersson 2020) on the same tonemap at the eye's pixels per degree"},
        {"temporal", "SVGF 5.4: mean |lum(out_t) - lum(out_t-1)| of the same variant, HDR Rec.709 luminance, "
                     "from the second frame of each (seed, eye) sequence"},
        {"regions", "fovea: gaze-centred disc; periphery: complement; eccN-M: view-ray angle to gaze in [N,M) deg"},
        {"vs_baseline", "ratio = geometric mean of paired per-frame ratios variant/baseline; ci_low/ci_high: "
                        "block-bootstrap interval; significant: the interval excludes 1"}};
    nlohmann::json scenes = nlohmann::json::object();
    for (const std::string& scene : results.Scenes()) {
        const SceneDesign& design = stats.Design(scene);
        nlohmann::json variants = nlohmann::json::object();
        for (const std::string& variant : results.Variants(scene)) {
            nlohmann::json regions = nlohmann::json::object();
            for (const std::string& region : results.Regions(scene)) {
                nlohmann::json metrics = nlohmann::json::object();
                for (const std::string& metric : results.Metrics(scene)) {
                    const MetricStats* m = stats.Find(scene, variant, region, metric);
                    if (!m || m->spread.count == 0) continue;
                    nlohmann::json entry = {{"mean", Number(m->spread.mean)},
                                            {"median", Number(m->spread.median)},
                                            {"geometric_mean", Number(m->spread.geometricMean)},
                                            {"count", m->spread.count}};
                    const MetricStats* base = stats.Find(scene, design.baseline, region, metric);
                    auto pct = base ? PercentRelative(m->spread.mean, base->spread.mean) : std::nullopt;
                    entry["percent_vs_baseline"] = pct ? nlohmann::json(*pct) : nlohmann::json(nullptr);
                    if (m->vsBaseline) {
                        const PairedRatio& r = *m->vsBaseline;
                        entry["vs_baseline"] = {{"ratio", Number(r.ratio)},
                                                {"ci_low", Number(r.lower)},
                                                {"ci_high", Number(r.upper)},
                                                {"confidence", stats.Options().confidence},
                                                {"significant", r.Significant()},
                                                {"win_rate", Number(r.winRate)},
                                                {"pairs", r.pairs},
                                                {"dropped", r.dropped},
                                                {"block_length", r.blockLength}};
                    }
                    if (m->dominant.Dominates())
                        entry["dominant_frames"] = {{"frames", m->dominant.frames}, {"share", m->dominant.share}};
                    metrics[metric] = entry;
                }
                if (!metrics.empty()) regions[region] = metrics;
            }
            variants[variant] = regions;
        }
        scenes[scene] = {{"seeds", design.seeds},
                         {"frames", design.frames},
                         {"eyes", design.eyes},
                         {"baseline", design.baseline},
                         {"variants", variants}};
    }
    j["scenes"] = scenes;
    return j;
}

void WriteSummaryJson(const std::filesystem::path& path, const Results& results, const ExperimentStats& stats) {
    WriteTextAtomically(path, SummaryJson(results, stats).dump(2) + "\n");
}

std::string SummaryTable(const Results& results, const ExperimentStats& stats) {
    std::string out;
    const auto [bLo, bHi] = stats.BlockLengthRange();
    const std::string blocks = bLo == bHi ? std::to_string(bLo) : fmt::format("{}-{}", bLo, bHi);
    for (const std::string& scene : results.Scenes()) {
        const SceneDesign& d = stats.Design(scene);
        out += fmt::format("Scene {}: {} seed{} ({}) x {} frames x {} eyes; baseline {}; relMSE eps = {:g}\n", scene,
                           d.seeds.size(), d.seeds.size() == 1 ? "" : "s", SeedList(d.seeds), d.frames, d.eyes,
                           d.baseline, results.relMseEpsilon);
        out += fmt::format(
            "  ratio: geometric mean of the per-frame ratios to {} (paired on seed, eye, frame), [{:g}% interval: "
            "circular block bootstrap, blocks of {} frames]\n  ns: the interval contains 1 (no significant "
            "change); win: share of pairs where the variant is better; temporal: mean |lum(t) - lum(t-1)|\n",
            d.baseline, 100.0 * stats.Options().confidence, blocks);
        // The variant column as wide as the longest name (two-history-asvgf-stable-hysteresis).
        size_t nameWidth = std::string_view("variant").size();
        for (const std::string& variant : results.Variants(scene)) nameWidth = std::max(nameWidth, variant.size());
        out += fmt::format("{:<{}} {:<9} {:>9} {:>9} {:>9}  {:<28} {:>4}  {:>9}  {:<28} {:>6}\n", "variant", nameWidth,
                           "region", "relMSE", "median", "geomean", "relMSE ratio [95% CI]", "win", "temporal",
                           "temporal ratio [95% CI]", "SSIM");
        bool anyZero = false;
        for (const std::string& variant : results.Variants(scene))
            for (const std::string& region : ComparedRegions()) {
                const MetricStats* e = stats.Find(scene, variant, region, "relmse");
                if (!e) continue;
                const bool zero = e->spread.count > 0 && std::isnan(e->spread.geometricMean);
                anyZero = anyZero || zero;
                const MetricStats* t = stats.Find(scene, variant, region, "temporal");
                const MetricStats* s = stats.Find(scene, variant, region, "ssim");
                const bool isBase = variant == d.baseline;
                auto ratio = [&](const MetricStats* m) {
                    return isBase ? std::string("baseline") : m && m->vsBaseline ? FormatRatio(*m->vsBaseline) : "-";
                };
                const std::string win = !isBase && e->vsBaseline && e->vsBaseline->pairs > 0
                                            ? fmt::format("{:.0f}%", 100.0 * e->vsBaseline->winRate)
                                            : "-";
                out += fmt::format("{:<{}} {:<9} {:>9} {:>9} {:>9}  {:<28} {:>4}  {:>9}  {:<28} {:>6}\n", variant,
                                   nameWidth, region, Sci(e->spread.mean), Sci(e->spread.median),
                                   zero ? "n/a" : Sci(e->spread.geometricMean),
                                   ratio(e), win, t ? Sci(t->spread.mean) : "-", ratio(t),
                                   s ? fmt::format("{:.4f}", s->spread.mean) : "-");
            }
        if (anyZero)
            out += "  geomean n/a: some frames have an error of exactly 0 (e.g. a fovea on the empty background), "
                   "where a geometric mean is undefined\n";
        std::string dominant;
        for (const std::string& variant : results.Variants(scene))
            for (const std::string& region : ComparedRegions()) {
                const MetricStats* e = stats.Find(scene, variant, region, "relmse");
                if (!e || !e->dominant.Dominates()) continue;
                std::string frames;
                for (size_t i = 0; i < e->dominant.frames.size() && i < 8; ++i)
                    frames += (i ? ", " : "") + std::to_string(e->dominant.frames[i]);
                if (e->dominant.frames.size() > 8) frames += ", ...";
                dominant += fmt::format("  {} {}: {} of {} frames ({}) hold {:.0f}% of the mean relMSE\n", variant,
                                        region, e->dominant.frames.size(), e->dominant.totalFrames, frames,
                                        100.0 * e->dominant.share);
            }
        if (!dominant.empty()) out += "Outlier frames (mean over eyes and seeds):\n" + dominant;
        out += "\n";
    }
    return out;
}

ReportTable PerSeedTable(const Results& results, const std::vector<VdpScore>& vdp) {
    struct Sum {
        double total = 0.0;
        size_t count = 0;
    };
    // (scene, seed, variant, region or "jod", metric) → sum and count.
    std::map<std::tuple<std::string, uint32_t, std::string, std::string, std::string>, Sum> sums;
    for (const ResultRow& r : results.rows()) {
        if (!std::isfinite(r.value)) continue;
        Sum& s = sums[{r.scene, r.seed, r.variant, r.region, r.metric}];
        s.total += r.value;
        ++s.count;
    }
    for (const VdpScore& v : vdp) {
        Sum& s = sums[{v.scene, v.seed, v.variant, "", "jod"}];
        s.total += v.jod;
        ++s.count;
    }
    const std::vector<std::pair<std::string, std::string>> columns = {
        {"whole", "relmse"}, {"fovea", "relmse"}, {"periphery", "relmse"}, {"whole", "ssim"}, {"whole", "flip"}, {"", "jod"}};
    ReportTable table{"Per seed (means over frames and eyes of each seed alone)",
                      {"scene", "seed", "variant", "relMSE whole", "relMSE fovea", "relMSE periphery", "SSIM",
                       "FLIP", "JOD"},
                      {}};
    for (const std::string& scene : results.Scenes())
        for (uint32_t seed : results.Seeds(scene))
            for (const std::string& variant : results.Variants(scene)) {
                std::vector<std::string> row = {scene, std::to_string(seed), variant};
                for (const auto& [region, metric] : columns) {
                    auto it = sums.find({scene, seed, variant, region, metric});
                    if (it == sums.end() || it->second.count == 0) {
                        row.push_back("–");
                        continue;
                    }
                    const double mean = it->second.total / double(it->second.count);
                    row.push_back(metric == "relmse" ? fmt::format("{:.3e}", mean)
                                  : metric == "jod"  ? fmt::format("{:.3f}", mean)
                                                     : fmt::format("{:.4f}", mean));
                }
                table.rows.push_back(std::move(row));
            }
    return table;
}

}  // namespace fovrt
