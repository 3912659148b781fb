#include "app/sweep_compare.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numeric>
#include <set>
#include <sstream>
#include <tuple>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "config/config_io.h"
#include "core/error.h"
#include "gaze/gaze_source.h"

namespace fovrt {
namespace {

namespace fs = std::filesystem;

nlohmann::json ParseJson(std::ifstream& in, const fs::path& path) {
    try {
        return nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        Fail("{}: not valid JSON ({})", path.string(), e.what());
    }
}

nlohmann::json ReadJson(const fs::path& path) {
    std::ifstream in(path);
    if (!in) Fail("{}: cannot open (is {} the output folder of a finished `fovrt experiment` sweep?)", path.string(),
                  path.parent_path().string());
    return ParseJson(in, path);
}

std::vector<std::string> SplitCsvLine(const std::string& line) {
    std::vector<std::string> fields;
    std::string field;
    std::istringstream in(line);
    while (std::getline(in, field, ',')) fields.push_back(field);
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    return fields;
}

double ParseNumber(const std::string& text, const fs::path& file, size_t line, const char* column) {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size())
        Fail("{}:{}: column {} is '{}', not a number", file.string(), line, column, text);
    return value;
}

std::vector<CurveRow> ReadCurvesCsv(const fs::path& file, size_t run) {
    std::ifstream in(file);
    if (!in) Fail("{}: cannot open (is {} a sampling-design sweep's output folder?)", file.string(), file.parent_path().string());
    std::string line;
    if (!std::getline(in, line) || line != kCurvesCsvHeader)
        Fail("{}:1: not a curves.csv of this fovrt (its header differs from '{}')", file.string(), kCurvesCsvHeader);
    const std::vector<std::string> columns = SplitCsvLine(kCurvesCsvHeader);
    std::vector<CurveRow> rows;
    for (size_t number = 2; std::getline(in, line); ++number) {
        if (line.empty()) continue;
        const std::vector<std::string> f = SplitCsvLine(line);
        if (f.size() != columns.size())
            Fail("{}:{}: {} fields, expected {}", file.string(), number, f.size(), columns.size());
        auto num = [&](size_t c) { return ParseNumber(f[c], file, number, columns[c].c_str()); };
        CurveRow r;
        r.scene = f[0], r.variant = f[1], r.design = f[2], r.budget = f[3];
        if (!r.budget.empty()) (void)num(3);  // a number, or empty for a design at its own sampling
        const double seed = num(4);
        if (seed < 0 || seed != std::floor(seed) || seed > 4294967295.0)
            Fail("{}:{}: column seed is '{}', not a seed", file.string(), number, f[4]);
        r.seed = uint32_t(seed);
        r.tracedWhole = num(5), r.tracedFovea = num(6), r.tracedPeriphery = num(7), r.guideRays = num(8);
        r.jod = num(9), r.jodSustained = num(10), r.jodTransient = num(11);
        r.relmseWhole = num(12), r.relmseFovea = num(13), r.flickerFovea = num(14);
        r.run = run;
        rows.push_back(std::move(r));
    }
    if (rows.empty()) Fail("{}: no rows", file.string());
    return rows;
}

// The first key (dotted) where two JSON values differ; empty when they are equal.
std::string FirstDifference(const nlohmann::json& a, const nlohmann::json& b, const std::string& prefix) {
    if (a.is_object() && b.is_object()) {
        std::set<std::string> keys;
        for (const auto& [k, v] : a.items()) keys.insert(k);
        for (const auto& [k, v] : b.items()) keys.insert(k);
        for (const std::string& k : keys) {
            const std::string path = prefix.empty() ? k : prefix + "." + k;
            if (!a.contains(k) || !b.contains(k)) return path;
            if (std::string d = FirstDifference(a[k], b[k], path); !d.empty()) return d;
        }
        return {};
    }
    return a == b ? std::string() : (prefix.empty() ? std::string("(the whole value)") : prefix);
}

// A key a run's manifest lacks was added to fovrt after that run, and the run ran at its default:
// a key is added with the default that keeps what runs did before it. So runs from either side of
// it compare, while a run that set the new key to anything else still differs.
void FillAbsentKeys(nlohmann::json& config, const nlohmann::json& defaults) {
    if (!config.is_object() || !defaults.is_object()) return;
    for (const auto& [key, value] : defaults.items()) {
        if (!config.contains(key)) config[key] = value;
        else FillAbsentKeys(config[key], value);
    }
}

using PointKey = std::tuple<std::string, std::string, std::string, std::string, size_t, uint32_t>;
PointKey KeyOf(const CurveRow& r) { return {r.scene, r.variant, r.design, r.budget, r.window, r.seed}; }

std::string PointText(const CurveRow& r, bool pooled) {
    return fmt::format("{} / {} / design {} at {} / {}seed {}", r.scene, r.variant, r.design,
                       r.budget.empty() ? "its own sampling" : r.budget + " spp",
                       pooled ? fmt::format("window w{} / ", r.window + 1) : "", r.seed);
}

// The keys of where the eye looks (GazeParams' rows, "gaze.source", …), not the tracker's.
bool IsEyePathKey(const std::string& key) {
    return std::any_of(GazeParamTable().begin(), GazeParamTable().end(),
                       [&](const SettingRow<GazeParams>& row) { return key == row.info.key; });
}

// The keys of where the eye looks, moved out of a run's config into their own object.
nlohmann::json TakeEyePath(nlohmann::json& config) {
    nlohmann::json eye = nlohmann::json::object();
    nlohmann::json& gaze = config["gaze"];
    for (auto it = gaze.begin(); it != gaze.end();)
        if (IsEyePathKey("gaze." + it.key())) eye[it.key()] = it.value(), it = gaze.erase(it);
        else ++it;
    return eye;
}

// Each window's keys that differ between the windows, as "gaze.key=value".
std::vector<std::string> DescribeWindows(const std::vector<nlohmann::json>& eyes) {
    if (eyes.size() <= 1) return {""};
    std::vector<std::string> out(eyes.size());
    for (const auto& [key, value] : eyes[0].items()) {
        const bool differs = std::any_of(eyes.begin(), eyes.end(), [&](const nlohmann::json& e) {
            return !e.contains(key) || e[key] != value;
        });
        if (!differs) continue;
        for (size_t w = 0; w < eyes.size(); ++w) {
            const nlohmann::json v = eyes[w].value(key, nlohmann::json());
            out[w] += fmt::format("{}gaze.{}={}", out[w].empty() ? "" : " ", key,
                                  v.is_string() ? v.get<std::string>() : v.dump());
        }
    }
    return out;
}

// Where two runs hold the same point and seed: the same scores (a deterministic sweep), the same
// rays to 1 % (a mean over each run's seeds).
void CheckSamePoint(const CurveRow& a, const CurveRow& b, const std::vector<fs::path>& runs, bool pooled) {
    const std::tuple<const char*, double, double> scores[] = {
        {"jod", a.jod, b.jod},
        {"jod_sustained", a.jodSustained, b.jodSustained},
        {"jod_transient", a.jodTransient, b.jodTransient},
        {"relmse_whole", a.relmseWhole, b.relmseWhole},
        {"relmse_fovea", a.relmseFovea, b.relmseFovea},
        {"flicker_fovea", a.flickerFovea, b.flickerFovea}};
    for (const auto& [name, x, y] : scores)
        if (x != y && !(std::isnan(x) && std::isnan(y)))  // a score a run did not take is NaN in both
            Fail("{} and {} disagree on {}: {} {:.9g} against {:.9g} (a sweep repeats its points to the last digit: "
                 "a different build, scene or input?)",
                 runs[a.run].string(), runs[b.run].string(), PointText(a, pooled), name, x, y);
    if (std::abs(a.tracedWhole - b.tracedWhole) > 0.01 * std::max(a.tracedWhole, b.tracedWhole))
        Fail("{} and {} measured {} rays apart on {}: {:.6g} against {:.6g} traced spp", runs[a.run].string(),
             runs[b.run].string(), "more than 1 %", PointText(a, pooled), a.tracedWhole, b.tracedWhole);
}

// The content each scene loaded, as its points' manifests record it (designs/<label>/manifest.json,
// "scenes"[].fingerprint): one scene with two fingerprints, in one run or two, means its files
// changed between the points, which a sweep's config cannot show.
class SceneContent {
public:
    void Check(const fs::path& run, const nlohmann::json& manifest) {
        for (const nlohmann::json& point : manifest["sweep"].value("points", nlohmann::json::array())) {
            const fs::path dir = run / "designs" / point.value("label", "");
            std::ifstream in(dir / "manifest.json");
            if (!in) Fail("{}: missing: the sweep {} is incomplete (its point {} has no manifest)", (dir / "manifest.json").string(),
                          run.string(), point.value("label", ""));
            for (const nlohmann::json& scene : ParseJson(in, dir / "manifest.json").value("scenes", nlohmann::json::array())) {
                if (!scene.is_object()) continue;
                const std::string name = scene.value("scene", ""), fingerprint = scene.value("fingerprint", "");
                const auto [it, added] = first_.try_emplace(name, fingerprint, dir);
                if (!added && it->second.first != fingerprint)
                    Fail("{} and {} loaded different content for scene '{}' (fingerprints {} and {}): its files changed "
                         "between them, so their points are not comparable",
                         it->second.second.string(), dir.string(), name, it->second.first, fingerprint);
            }
        }
    }

private:
    std::map<std::string, std::pair<std::string, fs::path>> first_;  // scene -> fingerprint, the point that loaded it
};

}  // namespace

GatheredCurves GatherSweepRuns(const std::vector<fs::path>& runs, GazeWindows gaze) {
    if (runs.empty()) Fail("rays-saved: name at least one sweep's output folder");
    const bool pooled = gaze == GazeWindows::kPooled;
    GatheredCurves out;
    out.runs = runs;
    nlohmann::json firstConfig;
    std::vector<nlohmann::json> eyes;  // each window's eye path
    std::map<std::string, std::pair<nlohmann::json, size_t>> designKeys;  // name -> keys, run
    std::map<PointKey, size_t> index;                                     // -> row in out.rows
    SceneContent content;
    const nlohmann::json defaults = ConfigToJson(RunConfig{});
    for (size_t r = 0; r < runs.size(); ++r) {
        const fs::path& run = runs[r];
        const nlohmann::json manifest = ReadJson(run / "manifest.json");
        if (!manifest.value("complete", false) || !manifest.contains("sweep") || !manifest.contains("config"))
            Fail("{}: not a finished sampling-design sweep (its manifest.json has no complete sweep)", run.string());
        nlohmann::json config = manifest["config"];
        FillAbsentKeys(config, defaults);
        config.erase("output");
        size_t window = 0;
        if (pooled) {
            const nlohmann::json eye = TakeEyePath(config);
            window = size_t(std::find(eyes.begin(), eyes.end(), eye) - eyes.begin());
            if (window == eyes.size()) eyes.push_back(eye);
        }
        if (r == 0) {
            firstConfig = config;
        } else if (const std::string key = FirstDifference(firstConfig, config, ""); !key.empty()) {
            Fail("{} and {} ran different configurations ({} differs): their points are not comparable{}",
                 runs[0].string(), run.string(), key,
                 IsEyePathKey(key) ? " (--pool-gaze gathers runs that differ only in where the eye looks)" : "");
        }
        content.Check(run, manifest);
        const nlohmann::json summary = ReadJson(run / "summary.json");
        if (!summary.contains("designs") || !summary["designs"].is_object())
            Fail("{}: summary.json has no designs", run.string());
        for (const auto& [name, design] : summary["designs"].items()) {
            const nlohmann::json keys = design.value("keys", nlohmann::json::object());
            auto [it, added] = designKeys.emplace(name, std::pair{keys, r});
            if (!added)
                if (const std::string key = FirstDifference(it->second.first, keys, ""); !key.empty())
                    Fail("{} and {} name different designs '{}' ({} differs): rename one", runs[it->second.second].string(),
                         run.string(), name, key);
        }
        for (CurveRow& row : ReadCurvesCsv(run / "curves.csv", r)) {
            row.window = window;
            auto [it, added] = index.emplace(KeyOf(row), out.rows.size());
            if (added)
                out.rows.push_back(std::move(row));
            else
                CheckSamePoint(out.rows[it->second], row, runs, pooled);
        }
    }
    // Windows numbered in the order of their gaze keys (numbers by value), not of the runs on the
    // command line: the labels and the bootstrap's units, hence its interval, do not depend on it.
    std::vector<size_t> order(eyes.size()), rank(eyes.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return eyes[a] < eyes[b]; });
    std::vector<nlohmann::json> sorted;
    for (size_t w = 0; w < order.size(); ++w) rank[order[w]] = w, sorted.push_back(eyes[order[w]]);
    for (CurveRow& row : out.rows)
        if (pooled) row.window = rank[row.window];
    out.windows = DescribeWindows(sorted);
    return out;
}

void KeepBudgets(GatheredCurves& curves, const std::vector<double>& budgets) {
    if (budgets.empty()) return;
    auto budgetOf = [](const CurveRow& r) { return std::stod(r.budget); };  // checked by ReadCurvesCsv
    for (double budget : budgets)
        if (std::none_of(curves.rows.begin(), curves.rows.end(),
                         [&](const CurveRow& r) { return !r.budget.empty() && budgetOf(r) == budget; }))
            Fail("rays-saved: --budget {:g}: no run holds a point at {:g} spp", budget, budget);
    std::erase_if(curves.rows, [&](const CurveRow& r) {
        return !r.budget.empty() && std::find(budgets.begin(), budgets.end(), budgetOf(r)) == budgets.end();
    });
}

std::vector<DesignComparison> CompareDesigns(const GatheredCurves& curves, const std::string& anchor,
                                             const std::vector<std::string>& designs) {
    // (scene, variant) -> design -> budget -> unit -> row
    using Points = std::map<std::string, std::map<SampleUnit, const CurveRow*>>;
    std::map<std::pair<std::string, std::string>, std::map<std::string, Points>> all;
    std::vector<std::string> order;  // designs in the order the runs list them
    for (const CurveRow& r : curves.rows) {
        all[{r.scene, r.variant}][r.design][r.budget][SampleUnit{r.window, r.seed}] = &r;
        if (std::find(order.begin(), order.end(), r.design) == order.end()) order.push_back(r.design);
    }
    auto known = [&](const std::string& d) { return std::find(order.begin(), order.end(), d) != order.end(); };
    if (!known(anchor)) Fail("rays-saved: no run holds the anchor design '{}'", anchor);
    std::vector<std::string> tests = designs;
    if (tests.empty())
        for (const std::string& d : order)
            if (d != anchor) tests.push_back(d);
    for (const std::string& d : tests)
        if (!known(d)) Fail("rays-saved: no run holds the design '{}'", d);

    std::vector<DesignComparison> out;
    for (const auto& [sceneVariant, byDesign] : all) {
        const auto anchorIt = byDesign.find(anchor);
        if (anchorIt == byDesign.end()) continue;
        for (const std::string& design : tests) {
            const auto testIt = byDesign.find(design);
            if (testIt == byDesign.end() || design == anchor) continue;
            // The units (window, seed) every point of both curves holds.
            std::set<SampleUnit> units;
            bool first = true;
            for (const Points* points : {&anchorIt->second, &testIt->second})
                for (const auto& [budget, byUnit] : *points) {
                    std::set<SampleUnit> here;
                    for (const auto& [unit, row] : byUnit) here.insert(unit);
                    if (first) units = here, first = false;
                    else {
                        std::set<SampleUnit> both;
                        std::set_intersection(units.begin(), units.end(), here.begin(), here.end(),
                                              std::inserter(both, both.begin()));
                        units = both;
                    }
                }
            DesignComparison c;
            c.units.assign(units.begin(), units.end());
            if (c.units.empty())
                Fail("rays-saved: {} / {}: no {} is common to every point of '{}' and '{}'", sceneVariant.first,
                     sceneVariant.second, curves.windows.size() > 1 ? "window and seed" : "seed", anchor, design);
            // A curve over those units, rays ascending; a point's rays are the mean of its units' (each
            // run's rows hold that run's mean; pooled windows' maps differ a little), whatever the runs' order.
            auto curveOf = [&](const Points& points, bool fovea, std::vector<std::string>* budgets) {
                SeededRateQualityCurve curve;
                std::vector<std::pair<SeededRateQualityPoint, std::string>> sorted;
                for (const auto& [budget, byUnit] : points) {
                    SeededRateQualityPoint p;
                    double rays = 0.0;
                    for (const SampleUnit& unit : c.units) {
                        const CurveRow* row = byUnit.at(unit);
                        rays += row->tracedWhole;
                        p.jodPerSeed.push_back(fovea ? FovealQuality(row->relmseFovea) : row->jod);
                    }
                    p.rays = rays / double(c.units.size());
                    sorted.emplace_back(std::move(p), budget);
                }
                std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.first.rays < b.first.rays; });
                for (auto& [p, budget] : sorted) {
                    if (budgets) budgets->push_back(budget);
                    curve.push_back(std::move(p));
                }
                return curve;
            };
            const SeededRateQualityCurve test = curveOf(testIt->second, false, &c.budgets);
            c.saved = CompareCurves(sceneVariant.first, sceneVariant.second, design, curveOf(anchorIt->second, false, nullptr),
                                    curveOf(anchorIt->second, true, nullptr), test, curveOf(testIt->second, true, nullptr));
            for (const SeededRateQualityPoint& p : test) {
                double sum = 0.0;
                for (double j : p.jodPerSeed) sum += j;
                c.rays.push_back(p.rays);
                c.jod.push_back(sum / double(p.jodPerSeed.size()));
            }
            out.push_back(std::move(c));
        }
    }
    return out;
}

std::string DesignComparisonText(const std::string& anchor, const std::vector<DesignComparison>& comparisons,
                                 const std::vector<std::string>& windows) {
    const bool pooled = windows.size() > 1;
    std::string out;
    if (pooled) {
        out += fmt::format("{} gaze windows pooled, each (window, seed) a unit of the bootstrap:\n", windows.size());
        for (size_t w = 0; w < windows.size(); ++w) out += fmt::format("  w{}  {}\n", w + 1, windows[w]);
    }
    std::vector<RaysSavedRow> rows;
    for (const DesignComparison& c : comparisons) rows.push_back(c.saved);
    out += RaysSavedTable(anchor, rows, pooled ? "window and seed" : "seed");
    ReportTable points{"", {"scene", "variant", "design", pooled ? "window:seed" : "seeds", "budget spp", "traced spp", "JOD",
                            "rays saved at this JOD [95 %]"}, {}};
    for (const DesignComparison& c : comparisons) {
        std::vector<std::string> units;
        for (const SampleUnit& u : c.units)
            units.push_back(pooled ? fmt::format("w{}:{}", u.window + 1, u.seed) : fmt::format("{}", u.seed));
        const std::string seeds = fmt::format("{}", fmt::join(units, " "));
        for (size_t i = 0; i < c.rays.size(); ++i) {
            points.rows.push_back({c.saved.scene, c.saved.variant, c.saved.design, seeds, c.budgets[i],
                                   fmt::format("{:.3f}", c.rays[i]), fmt::format("{:.3f}", c.jod[i]),
                                   IntervalText(c.saved.raysSavedAtPoints[i], "{:.2f}", "×")});
        }
    }
    return out + fmt::format("At each of a design's points (the {} both curves hold; the anchor's fit read at the point's JOD):\n",
                             pooled ? "units" : "seeds") +
           TextTable(points);
}

nlohmann::json DesignComparisonJson(const std::string& anchor, const std::vector<DesignComparison>& comparisons,
                                    const GatheredCurves& curves) {
    nlohmann::json runs = nlohmann::json::array(), list = nlohmann::json::array();
    for (const fs::path& run : curves.runs) runs.push_back(run.string());
    for (const DesignComparison& c : comparisons) {
        nlohmann::json units = nlohmann::json::array(), points = nlohmann::json::array();
        for (const SampleUnit& u : c.units) units.push_back({{"window", u.window + 1}, {"seed", u.seed}});
        for (size_t i = 0; i < c.rays.size(); ++i)
            points.push_back({{"budget_spp", c.budgets[i]},
                              {"traced_spp", c.rays[i]},
                              {"jod", c.jod[i]},
                              {"rays_saved_here", IntervalJson(c.saved.raysSavedAtPoints[i])}});
        list.push_back({{"scene", c.saved.scene},
                        {"variant", c.saved.variant},
                        {"design", c.saved.design},
                        {"units", units},
                        {"rays_saved", IntervalJson(c.saved.raysSaved)},
                        {"jod_gain", IntervalJson(c.saved.jodGain)},
                        {"rays_saved_fovea", IntervalJson(c.saved.raysSavedFovea)},
                        {"points", points}});
    }
    // The method's seeds are (window, seed) units where gaze windows were pooled, as the table says.
    return {{"anchor_design", anchor}, {"runs", runs}, {"windows", curves.windows},
            {"method", kRaysSavedMethod},
            {"bootstrap_unit", curves.windows.size() > 1 ? "window and seed" : "seed"},
            {"comparisons", list}};
}

std::string PerWindowText(const GatheredCurves& curves, const std::string& anchor,
                          const std::vector<std::string>& designs) {
    if (curves.windows.size() <= 1) return "";
    ReportTable table{"", {"window", "scene", "variant", "design", "units", "rays saved at equal JOD [95 %]",
                           "JOD gain at equal rays [95 %]"}, {}};
    for (size_t w = 0; w < curves.windows.size(); ++w) {
        GatheredCurves one{curves.runs, {}, {""}};
        std::copy_if(curves.rows.begin(), curves.rows.end(), std::back_inserter(one.rows),
                     [&](const CurveRow& r) { return r.window == w; });
        auto holds = [&](const std::string& d) {
            return std::any_of(one.rows.begin(), one.rows.end(), [&](const CurveRow& r) { return r.design == d; });
        };
        // A window that lacks a design (a run added to some windows only) is left out of its rows,
        // as the pooled comparison leaves it out of its units.
        std::vector<std::string> kept;
        for (const std::string& d : designs)
            if (holds(d)) kept.push_back(d);
        if (!holds(anchor) || (!designs.empty() && kept.empty())) continue;
        std::vector<DesignComparison> comparisons;
        try {
            comparisons = CompareDesigns(one, anchor, kept);
        } catch (const Error& e) {  // e.g. no seed common to every point here: the pooled table stands
            table.rows.push_back({fmt::format("w{}", w + 1), "—", "", "", "", e.what(), ""});
            continue;
        }
        for (const DesignComparison& c : comparisons)
            table.rows.push_back({fmt::format("w{}", w + 1), c.saved.scene, c.saved.variant, c.saved.design,
                                  fmt::format("{}", c.units.size()), IntervalText(c.saved.raysSaved, "{:.2f}", "×"),
                                  IntervalText(c.saved.jodGain, "{:+.3f}", "")});
    }
    return "Each window alone (its seeds the units of its interval):\n" + TextTable(table);
}

}  // namespace fovrt
