#include "app/sweep_outputs.h"

#include <cmath>
#include <cstdio>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/report_html.h"
#include "config/config_io.h"
#include "core/atomic_file.h"
#include "core/cpu_time.h"
#include "pipeline/build_info.h"

namespace fovrt {
namespace {

namespace fs = std::filesystem;

std::vector<uint32_t> SeedsOf(const ExperimentSpec& spec) {
    return spec.seeds.empty() ? std::vector<uint32_t>{spec.config.run.seed} : spec.seeds;
}

double Mean(const std::vector<double>& values) {
    if (values.empty()) return std::nan("");
    double sum = 0.0;
    for (double v : values) sum += v;
    return sum / double(values.size());
}

// The points of design `d`, budgets ascending.
std::vector<const SweepPointResult*> PointsOf(const ExperimentSpec& spec, const std::vector<SweepPointResult>& points,
                                              size_t d) {
    std::vector<const SweepPointResult*> out;
    for (const SweepPointResult& p : points)
        if (spec.sweep.points[p.point].design == d) out.push_back(&p);
    return out;
}

// The quality a curve plots against rays.
enum class CurveQuality {
    kJod,         // FovVideoVDP JOD
    kFovealError  // −ln foveal relMSE: higher is better, and its seed mean is the log of the geometric mean
};
constexpr const char* kFovealErrorName = "-ln foveal relMSE";

SeededRateQualityCurve CurveOf(const ExperimentSpec& spec, const std::vector<SweepPointResult>& points, size_t d,
                               const std::string& scene, const std::string& variant,
                               CurveQuality quality = CurveQuality::kJod) {
    SeededRateQualityCurve curve;
    for (const SweepPointResult* p : PointsOf(spec, points, d)) {
        const SweepPointValues v = PointValues(*p, scene, variant, SeedsOf(spec));
        std::vector<double> perSeed = v.jod;
        if (quality == CurveQuality::kFovealError)
            for (size_t s = 0; s < perSeed.size(); ++s) perSeed[s] = FovealQuality(v.relmseFovea[s]);
        curve.push_back({v.tracedSpp[0], perSeed});
    }
    return curve;
}

const RaysSavedRow* RowOf(const std::vector<RaysSavedRow>& rows, const std::string& scene, const std::string& variant,
                          const std::string& design) {
    for (const RaysSavedRow& r : rows)
        if (r.scene == scene && r.variant == variant && r.design == design) return &r;
    return nullptr;
}

std::string BudgetText(const SweepPoint& point) {
    return point.budgetSpp ? fmt::format("{:g}", *point.budgetSpp) : std::string();
}

std::string CurvesCsv(const ExperimentSpec& spec, const std::vector<SweepPointResult>& points) {
    const std::vector<uint32_t> seeds = SeedsOf(spec);
    std::string out = std::string(kCurvesCsvHeader) + "\n";
    for (const std::string& scene : points.front().scenes)
        for (const std::string& variant : spec.variants)
            for (const SweepPointResult& p : points) {
                const SweepPoint& point = spec.sweep.points[p.point];
                const SweepPointValues v = PointValues(p, scene, variant, seeds);
                for (size_t s = 0; s < seeds.size(); ++s)
                    out += fmt::format("{},{},{},{},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n",
                                       scene, variant, spec.sweep.designs[point.design].name, BudgetText(point),
                                       seeds[s], v.tracedSpp[0], v.tracedSpp[1], v.tracedSpp[2], v.guideRays, v.jod[s],
                                       v.jodSustained[s], v.jodTransient[s], v.relmseWhole[s], v.relmseFovea[s],
                                       v.flickerFovea[s]);
            }
    return out;
}

nlohmann::json SummaryJson(const ExperimentSpec& spec, const std::vector<SweepPointResult>& points,
                           const std::vector<RaysSavedRow>& saved) {
    const SamplingSweep& sweep = spec.sweep;
    const std::vector<uint32_t> seeds = SeedsOf(spec);
    nlohmann::json designs = nlohmann::json::object();
    for (size_t d = 0; d < sweep.designs.size(); ++d) {
        nlohmann::json keys = nlohmann::json::object();
        for (const auto& [key, value] : sweep.designs[d].keys) keys[key] = value;
        nlohmann::json pointsJson = nlohmann::json::array();
        const std::vector<const SweepPointResult*> designPoints = PointsOf(spec, points, d);
        for (size_t i = 0; i < designPoints.size(); ++i) {
            const SweepPointResult* p = designPoints[i];
            const SweepPoint& point = sweep.points[p->point];
            nlohmann::json traced = nlohmann::json::object(), variants = nlohmann::json::object();
            nlohmann::json guides = nlohmann::json::object();  // guide rays per pixel, whole image
            for (const std::string& scene : p->scenes) {
                for (const std::string& variant : spec.variants) {
                    const SweepPointValues v = PointValues(*p, scene, variant, seeds);
                    traced[scene] = {{"whole", v.tracedSpp[0]}, {"fovea", v.tracedSpp[1]}, {"periphery", v.tracedSpp[2]}};
                    guides[scene] = v.guideRays;
                    variants[scene][variant] = {{"jod", Mean(v.jod)},
                                                {"jod_per_seed", v.jod},
                                                {"jod_sustained", Mean(v.jodSustained)},
                                                {"jod_transient", Mean(v.jodTransient)},
                                                {"relmse_whole", Mean(v.relmseWhole)},
                                                {"relmse_fovea", Mean(v.relmseFovea)},
                                                {"flicker_fovea", Mean(v.flickerFovea)}};
                    if (const RaysSavedRow* row = RowOf(saved, scene, variant, sweep.designs[d].name))
                        variants[scene][variant]["rays_saved_here"] = IntervalJson(row->raysSavedAtPoints[i]);
                }
            }
            pointsJson.push_back({{"label", point.label},
                                  {"budget_spp", point.budgetSpp ? nlohmann::json(*point.budgetSpp) : nlohmann::json(nullptr)},
                                  {"outputs", (fs::path("designs") / point.label).string()},
                                  {"traced_spp", traced},
                                  {"guide_rays_per_pixel", guides},
                                  {"scores", variants}});
        }
        nlohmann::json raysSaved = nlohmann::json::object(), jodGain = nlohmann::json::object();
        nlohmann::json raysSavedFovea = nlohmann::json::object();
        for (const RaysSavedRow& r : saved)
            if (r.design == sweep.designs[d].name) {
                raysSaved[r.scene][r.variant] = IntervalJson(r.raysSaved);
                jodGain[r.scene][r.variant] = IntervalJson(r.jodGain);
                raysSavedFovea[r.scene][r.variant] = IntervalJson(r.raysSavedFovea);
            }
        designs[sweep.designs[d].name] = {{"keys", keys}, {"budgets_spp", sweep.designs[d].budgets}, {"points", pointsJson}};
        if (!raysSaved.empty()) {
            designs[sweep.designs[d].name]["rays_saved"] = raysSaved;
            designs[sweep.designs[d].name]["jod_gain"] = jodGain;
            designs[sweep.designs[d].name]["rays_saved_fovea"] = raysSavedFovea;
        }
    }
    return {{"anchor_design", sweep.anchor ? nlohmann::json(sweep.designs[*sweep.anchor].name) : nlohmann::json(nullptr)},
            {"budgets_spp", sweep.budgets},
            {"seeds", seeds},
            {"method", kRaysSavedMethod},
            {"designs", designs}};
}

// The anchor design's name, empty without one.
std::string AnchorName(const ExperimentSpec& spec) {
    return spec.sweep.anchor ? spec.sweep.designs[*spec.sweep.anchor].name : std::string();
}

ReportTable HeadlineReportTable(const std::string& anchor, const std::vector<RaysSavedRow>& rows) {
    ReportTable t{fmt::format("Rays saved at equal perceived quality against '{}'", anchor.empty() ? "—" : anchor),
                  {"scene", "variant", "design", "rays saved at equal JOD [95 %]", "JOD gain at equal rays [95 %]",
                   "rays saved at equal foveal relMSE [95 %]"},
                  {}};
    for (const RaysSavedRow& r : rows)
        t.rows.push_back({r.scene, r.variant, r.design, IntervalText(r.raysSaved, "{:.2f}", "×"),
                          IntervalText(r.jodGain, "{:+.3f}", ""), IntervalText(r.raysSavedFovea, "{:.2f}", "×")});
    return t;
}

ReportTable PointsTable(const ExperimentSpec& spec, const std::vector<SweepPointResult>& points,
                        const std::vector<RaysSavedRow>& saved) {
    ReportTable t{"Every point: measured sampling and scores (mean over seeds)",
                  {"scene", "variant", "design", "budget spp", "traced spp whole / fovea / periphery", "guide rays/pixel", "JOD",
                   "rays saved at this JOD [95 %]", "relMSE whole", "relMSE fovea", "flicker fovea"},
                  {}};
    for (const std::string& scene : points.front().scenes)
        for (const std::string& variant : spec.variants)
            for (size_t d = 0; d < spec.sweep.designs.size(); ++d) {
                const std::vector<const SweepPointResult*> designPoints = PointsOf(spec, points, d);
                const RaysSavedRow* row = RowOf(saved, scene, variant, spec.sweep.designs[d].name);
                for (size_t i = 0; i < designPoints.size(); ++i) {
                    const SweepPoint& point = spec.sweep.points[designPoints[i]->point];
                    const SweepPointValues v = PointValues(*designPoints[i], scene, variant, SeedsOf(spec));
                    const std::string here = row ? IntervalText(row->raysSavedAtPoints[i], "{:.2f}", "×") : "";
                    t.rows.push_back({scene, variant, spec.sweep.designs[d].name, BudgetText(point),
                                      fmt::format("{:.2f} / {:.2f} / {:.2f}", v.tracedSpp[0], v.tracedSpp[1], v.tracedSpp[2]),
                                      fmt::format("{:.3f}", v.guideRays), fmt::format("{:.3f}", Mean(v.jod)), here,
                                      fmt::format("{:.4g}", Mean(v.relmseWhole)), fmt::format("{:.4g}", Mean(v.relmseFovea)),
                                      fmt::format("{:.4g}", Mean(v.flickerFovea))});
                }
            }
    return t;
}

// A plot of something per point against the measured rays (log axis, a dot at every point).
LinePlot PlotAgainstRays(std::string title, std::string yLabel) {
    LinePlot plot;
    plot.title = std::move(title);
    plot.xLabel = "traced path samples per pixel (measured)";
    plot.yLabel = std::move(yLabel);
    plot.logX = true;
    plot.markers = true;
    return plot;
}

std::vector<std::string> CurvePlots(const ExperimentSpec& spec, const std::vector<SweepPointResult>& points,
                                    const std::vector<RaysSavedRow>& saved) {
    std::vector<std::string> plots;
    for (const std::string& scene : points.front().scenes)
        for (const std::string& variant : spec.variants) {
            LinePlot plot = PlotAgainstRays(fmt::format("{} · {}: JOD against rays", scene, variant), "JOD");
            for (size_t d = 0; d < spec.sweep.designs.size(); ++d) {
                PlotSeries series{spec.sweep.designs[d].name, {}};
                for (const SeededRateQualityPoint& q : CurveOf(spec, points, d, scene, variant))
                    series.points.emplace_back(q.rays, Mean(q.jodPerSeed));
                plot.series.push_back(std::move(series));
            }
            plots.push_back(SvgLinePlot(plot));
        }
    // How the saving changes with the budget: each design's rays saved at its own points' JOD.
    for (const std::string& scene : points.front().scenes)
        for (const std::string& variant : spec.variants) {
            LinePlot plot = PlotAgainstRays(fmt::format("{} · {}: rays saved at each point", scene, variant),
                                            "rays saved at this JOD (×)");
            for (size_t d = 0; d < spec.sweep.designs.size(); ++d) {
                const RaysSavedRow* row = RowOf(saved, scene, variant, spec.sweep.designs[d].name);
                if (!row) continue;
                PlotSeries series{spec.sweep.designs[d].name, {}, int(d)};  // the JOD plot's colour
                const SeededRateQualityCurve curve = CurveOf(spec, points, d, scene, variant);
                for (size_t i = 0; i < curve.size(); ++i)
                    if (row->raysSavedAtPoints[i].estimate.Ok())
                        series.points.emplace_back(curve[i].rays, row->raysSavedAtPoints[i].estimate.value);
                if (!series.points.empty()) plot.series.push_back(std::move(series));
            }
            if (!plot.series.empty()) plots.push_back(SvgLinePlot(plot));
        }
    return plots;
}

}  // namespace

nlohmann::json IntervalJson(const BjontegaardInterval& r) {
    nlohmann::json j = {{"value", r.estimate.Ok() ? nlohmann::json(r.estimate.value) : nlohmann::json(nullptr)}};
    if (!r.estimate.Ok()) {
        j["reason"] = r.estimate.reason;
        return j;
    }
    j["over"] = {r.estimate.from, r.estimate.to};
    if (r.intervalReason.empty()) {
        j["lower"] = r.lower;
        j["upper"] = r.upper;
    } else {
        j["interval_reason"] = r.intervalReason;
    }
    j["failed_resamples"] = r.failedReplicates;
    return j;
}

std::string IntervalText(const BjontegaardInterval& r, const char* format, const char* unit) {
    if (!r.estimate.Ok()) return "— (" + r.estimate.reason + ")";
    std::string text = fmt::format(fmt::runtime(format), r.estimate.value) + unit;
    if (r.intervalReason.empty())
        text += fmt::format(fmt::runtime(std::string(" [") + format + ", " + format + "]"), r.lower, r.upper);
    else
        text += " (no interval: " + r.intervalReason + ")";
    return text;
}

SweepPointValues PointValues(const SweepPointResult& point, const std::string& scene, const std::string& variant,
                             const std::vector<uint32_t>& seeds) {
    SweepPointValues v;
    if (auto it = point.tracedSpp.find(scene); it != point.tracedSpp.end()) v.tracedSpp = it->second;
    if (auto it = point.guideRays.find(scene); it != point.guideRays.end()) v.guideRays = it->second;
    const size_t n = seeds.size();
    auto seedIndex = [&](uint32_t seed) { return size_t(std::find(seeds.begin(), seeds.end(), seed) - seeds.begin()); };
    // Sums and counts per seed of each value.
    std::array<std::vector<double>, 6> sums, counts;
    for (size_t k = 0; k < sums.size(); ++k) sums[k].assign(n, 0.0), counts[k].assign(n, 0.0);
    auto add = [&](size_t k, size_t s, double value) {
        if (s < n) sums[k][s] += value, counts[k][s] += 1.0;
    };
    for (const VdpScore& score : point.vdp)
        if (score.scene == scene && score.variant == variant) {
            const size_t s = seedIndex(score.seed);
            add(0, s, score.jod), add(1, s, score.jodSustained), add(2, s, score.jodTransient);
        }
    for (const ResultRow& row : point.results.rows()) {
        if (row.scene != scene || row.variant != variant) continue;
        const size_t s = seedIndex(row.seed);
        if (row.metric == "relmse" && row.region == "whole") add(3, s, row.value);
        if (row.metric == "relmse" && row.region == "fovea") add(4, s, row.value);
        if (row.metric == "temporal" && row.region == "fovea") add(5, s, row.value);
    }
    std::array<std::vector<double>*, 6> out = {&v.jod, &v.jodSustained, &v.jodTransient,
                                               &v.relmseWhole, &v.relmseFovea, &v.flickerFovea};
    for (size_t k = 0; k < out.size(); ++k)
        for (size_t s = 0; s < n; ++s)
            out[k]->push_back(counts[k][s] > 0 ? sums[k][s] / counts[k][s] : std::nan(""));
    return v;
}

RaysSavedRow CompareCurves(std::string scene, std::string variant, std::string design, const SeededRateQualityCurve& anchor,
                           const SeededRateQualityCurve& anchorFovea, const SeededRateQualityCurve& test,
                           const SeededRateQualityCurve& testFovea) {
    BjontegaardIntervalOptions fovea;
    fovea.quality = kFovealErrorName;
    std::vector<BjontegaardInterval> atPoints;
    for (const SeededRateQualityPoint& point : test) atPoints.push_back(BootstrapRaysSavedAtPoint(anchor, point));
    return {std::move(scene),
            std::move(variant),
            std::move(design),
            BootstrapBjontegaardDelta(anchor, test, RateQualityDelta::kRaysSaved),
            BootstrapBjontegaardDelta(anchor, test, RateQualityDelta::kJodGain),
            BootstrapBjontegaardDelta(anchorFovea, testFovea, RateQualityDelta::kRaysSaved, fovea),
            std::move(atPoints)};
}

std::vector<RaysSavedRow> SweepRaysSaved(const ExperimentSpec& spec, const std::vector<SweepPointResult>& points) {
    std::vector<RaysSavedRow> rows;
    const SamplingSweep& sweep = spec.sweep;
    if (!sweep.anchor || points.empty()) return rows;
    for (const std::string& scene : points.front().scenes)
        for (const std::string& variant : spec.variants) {
            const SeededRateQualityCurve anchor = CurveOf(spec, points, *sweep.anchor, scene, variant);
            const SeededRateQualityCurve anchorFovea =
                CurveOf(spec, points, *sweep.anchor, scene, variant, CurveQuality::kFovealError);
            for (size_t d = 0; d < sweep.designs.size(); ++d) {
                if (d == *sweep.anchor) continue;
                rows.push_back(CompareCurves(scene, variant, sweep.designs[d].name, anchor, anchorFovea,
                                             CurveOf(spec, points, d, scene, variant),
                                             CurveOf(spec, points, d, scene, variant, CurveQuality::kFovealError)));
            }
        }
    return rows;
}

std::string TextTable(const ReportTable& t) {
    std::vector<size_t> widths(t.header.size(), 0);
    for (size_t c = 0; c < t.header.size(); ++c) {
        widths[c] = t.header[c].size();
        for (const auto& row : t.rows) widths[c] = std::max(widths[c], row[c].size());
    }
    auto line = [&](const std::vector<std::string>& cells) {
        std::string l = " ";
        for (size_t c = 0; c < cells.size(); ++c) l += " " + cells[c] + std::string(widths[c] - cells[c].size() + 1, ' ');
        while (!l.empty() && l.back() == ' ') l.pop_back();
        return l + "\n";
    };
    std::string out = line(t.header);
    for (const auto& row : t.rows) out += line(row);
    return out;
}

std::string RaysSavedTable(const std::string& anchor, const std::vector<RaysSavedRow>& rows, const std::string& unit) {
    const ReportTable t = HeadlineReportTable(anchor, rows);
    std::string out = t.title +
                      " (FovVideoVDP JOD, and foveal relMSE: what the eye looks at; Bjøntegaard delta on PCHIP fits, 95 % " +
                      unit + " bootstrap)\n";
    if (rows.empty()) {
        return out + (!anchor.empty() ? "  (no design besides the anchor)\n"
                                      : "  (no anchor: name one with experiment.anchor_design, or list one uniform design)\n");
    }
    return out + TextTable(t);
}

void WriteSweepOutputs(const ExperimentSpec& spec, const std::vector<SweepPointResult>& points,
                       const fs::path& outDir, std::chrono::steady_clock::time_point start) {
    const SamplingSweep& sweep = spec.sweep;
    const std::vector<RaysSavedRow> saved = SweepRaysSaved(spec, points);
    WriteTextAtomically(outDir / "curves.csv", CurvesCsv(spec, points));
    WriteTextAtomically(outDir / "summary.json", SummaryJson(spec, points, saved).dump(2) + "\n");
    const std::string headline = RaysSavedTable(AnchorName(spec), saved);
    const double wall = MsSince(start) / 1000.0, cpu = CpuSeconds();

    if (spec.config.output.report) {
        HtmlReport report;
        report.title = fmt::format("fovrt experiment: {}{} — sampling designs", spec.file.filename().string(),
                                   spec.quick ? " (--quick)" : "");
        std::string designs;
        for (const SamplingDesign& d : sweep.designs) designs += (designs.empty() ? "" : ", ") + d.name;
        std::string budgets;  // "1, 2, 4", or per design where they differ
        for (const SamplingDesign& d : sweep.designs) {
            std::string list;
            for (double b : d.budgets) list += (list.empty() ? "" : ", ") + fmt::format("{:g}", b);
            if (d.budgets != sweep.budgets || sweep.budgets.empty())
                budgets += fmt::format("{}{}: {}", budgets.empty() ? "" : "; ", d.name, list.empty() ? "its own sampling" : list);
        }
        if (budgets.empty())
            for (double b : sweep.budgets) budgets += (budgets.empty() ? "" : ", ") + fmt::format("{:g}", b);
        report.manifest = {{"experiment", spec.file.string()},
                           {"designs", designs},
                           {"anchor design", sweep.anchor ? sweep.designs[*sweep.anchor].name : "none"},
                           {"budgets (mean spp)", budgets},
                           {"resolution per eye", fmt::format("{}×{}", spec.config.camera.width, spec.config.camera.height)},
                           {"frames", ScoredFramesText(spec.config.run)},
                           {"points' outputs", "designs/<design>-b<budget>/ (each with its own report)"},
                           {"time", fmt::format("{:.1f} s wall, {:.1f} s CPU", wall, cpu)}};
        report.headline.push_back(HeadlineReportTable(AnchorName(spec), saved));
        report.plots = CurvePlots(spec, points, saved);
        report.tables.push_back(PointsTable(spec, points, saved));
        WriteHtmlReport(outDir / "report.html", report);
    }

    nlohmann::json manifest;
    manifest["command"] = "experiment";
    manifest["complete"] = true;
    manifest["experiment_file"] = spec.file.string();
    manifest["quick"] = spec.quick;
    manifest["scenes"] = spec.scenes;
    manifest["variants"] = spec.variants;
    manifest["seeds"] = SeedsOf(spec);
    nlohmann::json pointsJson = nlohmann::json::array();
    for (const SweepPoint& p : sweep.points)
        pointsJson.push_back({{"label", p.label},
                              {"design", sweep.designs[p.design].name},
                              {"budget_spp", p.budgetSpp ? nlohmann::json(*p.budgetSpp) : nlohmann::json(nullptr)},
                              {"ray_budget", p.config.foveation.rayBudget}});
    manifest["sweep"] = {{"points", pointsJson},
                         {"anchor_design", sweep.anchor ? nlohmann::json(sweep.designs[*sweep.anchor].name) : nlohmann::json(nullptr)}};
    manifest["config"] = ConfigToJson(spec.config);
    if (spec.merge) manifest["merged_shards"] = true;
    manifest["build"] = BuildInfoJson();
    manifest["total_s"] = wall;
    manifest["cpu_s"] = cpu;
    WriteTextAtomically(outDir / "manifest.json", manifest.dump(2) + "\n");

    std::printf("%s", headline.c_str());
    std::fprintf(stderr, "fovrt experiment: %zu points (%zu designs) done in %.1f s wall, %.1f s CPU -> %s\n",
                 sweep.points.size(), sweep.designs.size(), wall, cpu, outDir.string().c_str());
    if (spec.config.output.report) std::printf("HTML report: %s\n", (outDir / "report.html").string().c_str());
}

}  // namespace fovrt
