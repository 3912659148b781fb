// Sampling designs as an experiment axis (app/sampling_designs.h, app/sweep_outputs.h): the points
// an experiment file's designs and budgets make, every refusal naming the design and key, and the
// rays saved computed from the points' scores, on synthetic curves whose answer is known in closed
// form, in one sweep and from sweeps that ran apart (app/sweep_compare.h).
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "app/experiment.h"
#include "app/sweep_compare.h"
#include "app/sweep_outputs.h"
#include "app_test_configs.h"
#include "config/config_cli.h"
#include "core/error.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;

namespace {

ConfigOptions DesignOptions(const std::string& name, const std::string& lines) {
    return test::SmallExperimentOptions(test::ScratchDir("fovrt_designs") / name, {.experimentLines = lines});
}

std::string LoadError(const ConfigOptions& options, const ExperimentArgs& args = {}) {
    try {
        (void)LoadExperiment(options, args);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

constexpr const char* kTwoDesigns =
    "budgets = [2.5, 1]\n"
    "[experiment.designs.zeta]\n"
    "foveation.model = \"uniform\"\n"
    "[experiment.designs.alpha]\n"
    "foveation = { model = \"disc\", spp_inside = 6 }\n"
    "gaze.tracker_latency_ms = 40\n";

}  // namespace

TEST_CASE("designs × budgets: the points, in the file's order, each the experiment with its design and budget",
          "[app][designs]") {
    const ExperimentSpec spec = LoadExperiment(DesignOptions("points", kTwoDesigns));
    const SamplingSweep& sweep = spec.sweep;
    REQUIRE(sweep.Active());
    REQUIRE(sweep.designs.size() == 2);
    CHECK(sweep.designs[0].name == "zeta");  // the file's order, not the alphabet's
    CHECK(sweep.designs[1].name == "alpha");
    CHECK(sweep.budgets == std::vector<double>{1.0, 2.5});
    REQUIRE(sweep.anchor);
    CHECK(*sweep.anchor == 0);  // the one uniform design
    REQUIRE(sweep.points.size() == 4);
    CHECK(sweep.points[0].label == "zeta-b1");
    CHECK(sweep.points[1].label == "zeta-b2.5");
    CHECK(sweep.points[3].label == "alpha-b2.5");
    const int64_t pixels = 32 * 18;
    CHECK(sweep.points[0].config.foveation.rayBudget == pixels);
    CHECK(sweep.points[1].config.foveation.rayBudget == std::llround(2.5 * pixels));
    CHECK(sweep.points[1].config.foveation.model == "uniform");
    CHECK(sweep.points[3].config.foveation.model == "disc");
    CHECK(sweep.points[3].config.foveation.sppInside == 6);
    CHECK(sweep.points[3].config.gaze.tracker.latencyMs == 40.0);
    CHECK(sweep.points[1].config.gaze.tracker.latencyMs == 0.0);  // a design's keys stay in it
    // Everything else is the experiment's, denoisers included.
    CHECK(sweep.points[2].config.camera.width == spec.config.camera.width);
    CHECK(sweep.points[2].config.denoise.denoisers == spec.variants);
    // The experiment's own config keeps no budget.
    CHECK(spec.config.foveation.rayBudget == 0);
}

TEST_CASE("a design's keys go over [experiment.quick]; run_designs picks some", "[app][designs]") {
    const ConfigOptions options = DesignOptions("quick", std::string(kTwoDesigns) +
                                                             "[experiment.quick.foveation]\nspp_inside = 3\n"
                                                             "[experiment.quick.experiment]\nrun_designs = [\"alpha\"]\n");
    const ExperimentSpec full = LoadExperiment(options);
    CHECK(full.sweep.points.size() == 4);
    ExperimentArgs args;
    args.quick = true;
    const ExperimentSpec quick = LoadExperiment(options, args);
    REQUIRE(quick.sweep.points.size() == 2);
    CHECK(quick.sweep.points[0].label == "alpha-b1");
    CHECK(quick.sweep.points[0].config.foveation.sppInside == 6);
    CHECK_FALSE(quick.sweep.anchor);  // the uniform design does not run
}

TEST_CASE("a bad design is refused in one line naming the design and key", "[app][designs]") {
    using Catch::Matchers::Contains;
    CHECK_THAT(LoadError(DesignOptions("bad-key", "[experiment.designs.d]\nrender.max_depth = 3\n")),
               Contains("experiment.designs.d.render.max_depth") && Contains("[foveation]"));
    CHECK_THAT(LoadError(DesignOptions("gaze-source", "[experiment.designs.d]\ngaze.source = \"static\"\n")),
               Contains("experiment.designs.d.gaze.source"));
    CHECK_THAT(LoadError(DesignOptions("budget-key", "budgets = [1, 2]\n[experiment.designs.d]\nfoveation.ray_budget = 900\n")),
               Contains("experiment.designs.d.foveation.ray_budget") && Contains("experiment.budgets"));
    CHECK_THAT(LoadError(DesignOptions("bad-value", "[experiment.designs.d]\nfoveation.spp_inside = 99\n")),
               Contains("experiment.designs.d") && Contains("foveation.spp_inside"));
    CHECK_THAT(LoadError(DesignOptions("budget-range", "budgets = [65]\n[experiment.designs.d]\nfoveation.model = \"uniform\"\n")),
               Contains("experiment.budgets"));
    // 20 spp on average is past the default cap of 16 per pixel for a shaped map; a design that
    // raises it may sweep it, and uniform sampling, with no peak for the cap to bound, may too.
    CHECK_THAT(LoadError(DesignOptions("capped", "budgets = [20]\n[experiment.designs.d]\nfoveation.model = \"linear\"\n")),
               Contains("experiment.designs.d at budget 20 spp") && Contains("spp_cap"));
    CHECK_NOTHROW(LoadExperiment(DesignOptions("raised-cap", "budgets = [20]\n[experiment.designs.d]\n"
                                                             "foveation = { model = \"linear\", spp_cap = 32 }\n")));
    CHECK_NOTHROW(LoadExperiment(DesignOptions("uniform-20", "budgets = [20]\n[experiment.designs.d]\n"
                                                             "foveation.model = \"uniform\"\n")));
    // Half a sample per pixel needs a design whose floor lets the budget scale pixels below 1.
    CHECK_THAT(LoadError(DesignOptions("infeasible", "budgets = [0.5, 1]\n[experiment.designs.d]\nfoveation.model = \"uniform\"\n")),
               Contains("experiment.designs.d at budget 0.5 spp") && Contains("foveation.ray_budget") &&
                   Contains("spp_floor"));
    // A design that cannot go below 1 spp sweeps its own budgets beside the others'.
    const ExperimentSpec own = LoadExperiment(DesignOptions(
        "own-budgets", "budgets = [0.5, 1]\n[experiment.designs.u]\nfoveation = { model = \"uniform\", spp_floor = 0.0625 }\n"
                       "[experiment.designs.d]\nfoveation.model = \"disc\"\nbudgets = [1, 2, 4]\n"));
    REQUIRE(own.sweep.points.size() == 5);
    CHECK(own.sweep.points[0].label == "u-b0.5");
    CHECK(own.sweep.points[2].label == "d-b1");
    CHECK(own.sweep.points[4].config.foveation.rayBudget == 4 * 32 * 18);
    CHECK_NOTHROW(LoadExperiment(DesignOptions("feasible", "budgets = [0.5, 1]\n[experiment.designs.d]\n"
                                                           "foveation = { model = \"uniform\", spp_floor = 0.0625 }\n")));
    CHECK_THAT(LoadError(DesignOptions("no-designs", "budgets = [1, 2]\n")), Contains("experiment.budgets needs experiment.designs"));
    CHECK_THAT(LoadError(DesignOptions("anchor", "anchor_design = \"omega\"\n" + std::string(kTwoDesigns))),
               Contains("experiment.anchor_design"));
    CHECK_THAT(LoadError(DesignOptions("run", "run_designs = [\"omega\"]\n" + std::string(kTwoDesigns))),
               Contains("experiment.run_designs") && Contains("omega"));
    ConfigOptions set = DesignOptions("set", kTwoDesigns);
    set.sets = {"foveation.spp_inside=4"};
    CHECK_THAT(LoadError(set), Contains("--set foveation.spp_inside=4") && Contains("experiment.designs.alpha"));
    ConfigOptions noVdp = DesignOptions("no-vdp", kTwoDesigns);
    noVdp.sets = {"metric.vdp=false"};
    CHECK_THAT(LoadError(noVdp), Contains("metric.vdp"));
}

namespace {

// The options of SmallExperimentOptions' experiment with `variants` in place of its own.
// `sets`: --set options (the file already has its [foveation] table).
ConfigOptions VariantsOptions(const std::string& name, const std::string& variants, const std::string& lines,
                              std::vector<std::string> sets = {}) {
    ConfigOptions options = DesignOptions(name, lines);
    options.sets = std::move(sets);
    std::ifstream in(options.configPath);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string from = "variants = [\"svgf\", \"two-history\"]";
    const size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    text.replace(at, from.size(), "variants = " + variants);
    std::ofstream(options.configPath) << text;
    return options;
}

}  // namespace

// The RAE takes pixels without a path sample (filled from their neighbours): every point runs it,
// below 1 spp too, and so does the experiment's own sampling.
TEST_CASE("the RAE runs every point, those whose sampling goes below 1 spp included", "[app][designs]") {
    CHECK_NOTHROW(LoadExperiment(VariantsOptions("rae-own", "[\"svgf\", \"rae\"]", "", {"foveation.spp_outside=0.5"})));
    const ExperimentSpec spec = LoadExperiment(VariantsOptions("rae-budget", "[\"rae-spp\"]",
                                                               "budgets = [0.5, 1]\n[experiment.designs.u]\n"
                                                               "foveation = { model = \"uniform\", spp_floor = 0.0625 }\n"));
    REQUIRE(spec.sweep.points.size() == 2);
    CHECK(spec.sweep.points[0].config.denoise.denoisers == std::vector<std::string>{"rae-spp"});
}

namespace {

using SeedCurve = std::function<double(double, uint32_t)>;

// A point of a synthetic sweep: every seed's JOD from `jod(rays, seed)` and foveal relMSE from
// `fovealRelMse(rays, seed)` on one scene and variant, sampled as measured at `rays`.
SweepPointResult SyntheticPoint(size_t index, double rays, const SeedCurve& jod, const SeedCurve& fovealRelMse) {
    SweepPointResult p;
    p.point = index;
    p.scenes = {"room"};
    p.tracedSpp["room"] = {rays, rays, rays};
    for (uint32_t seed : {1u, 2u, 3u})
        for (int eye = 0; eye < 2; ++eye) {
            p.vdp.push_back({"room", seed, eye, "svgf", jod(rays, seed), 9.0, 9.5});
            p.results.Add({"room", 0, eye, "svgf", "fovea", "relmse", fovealRelMse(rays, seed), seed});
        }
    return p;
}

// The closed-form sweep: JOD = 7 + 0.8 ln(rays) (+ a per-seed offset that cancels in the paired
// bootstrap) for uniform; the foveated design `fov` scores as uniform does with twice its rays:
// rays saved exactly 2, JOD gain 0.8 ln 2 at every rate. Its fovea's relMSE is uniform's with three
// times its rays (relMSE ∝ 1/rays, a per-seed factor): rays saved at equal foveal relMSE exactly 3.
double ClosedFormUniformJod(double rays, uint32_t seed) { return 7.0 + 0.8 * std::log(rays) + 0.01 * seed; }

ExperimentSpec ClosedFormSpec(const std::string& name) {
    ExperimentSpec spec = LoadExperiment(DesignOptions(name,
                                                       "budgets = [1, 2, 4, 8]\n"
                                                       "[experiment.designs.uniform]\nfoveation.model = \"uniform\"\n"
                                                       "[experiment.designs.fov]\nfoveation.model = \"linear\"\n"));
    spec.seeds = {1, 2, 3};
    spec.variants = {"svgf"};
    return spec;
}

// `saved`: the design scores as uniform does with that many times its rays; `offset`: added to
// every JOD (another window's content).
std::vector<SweepPointResult> ClosedFormPoints(const ExperimentSpec& spec, double saved = 2.0, double offset = 0.0) {
    auto uniform = [offset](double rays, uint32_t seed) { return ClosedFormUniformJod(rays, seed) + offset; };
    auto foveated = [=](double rays, uint32_t seed) { return uniform(saved * rays, seed); };
    auto uniformFovea = [](double rays, uint32_t seed) { return 0.1 * (1.0 + 0.05 * seed) / rays; };
    auto foveatedFovea = [&](double rays, uint32_t seed) { return uniformFovea(3.0 * rays, seed); };
    std::vector<SweepPointResult> points;
    for (size_t i = 0; i < spec.sweep.points.size(); ++i) {
        const bool anchor = spec.sweep.points[i].design == 0;
        points.push_back(SyntheticPoint(i, *spec.sweep.points[i].budgetSpp,
                                        anchor ? SeedCurve(uniform) : SeedCurve(foveated),
                                        anchor ? SeedCurve(uniformFovea) : SeedCurve(foveatedFovea)));
    }
    return points;
}

}  // namespace

TEST_CASE("rays saved from the points: a design that reaches each JOD with half the rays saves 2×", "[app][designs]") {
    const ExperimentSpec spec = ClosedFormSpec("closed-form");
    const std::vector<SweepPointResult> points = ClosedFormPoints(spec);
    const std::vector<RaysSavedRow> rows = SweepRaysSaved(spec, points);
    REQUIRE(rows.size() == 1);
    CHECK(rows[0].design == "fov");
    REQUIRE(rows[0].raysSaved.estimate.Ok());
    CHECK(rows[0].raysSaved.estimate.value == Approx(2.0).epsilon(1e-3));
    CHECK(rows[0].jodGain.estimate.value == Approx(0.8 * std::log(2.0)).epsilon(1e-3));
    CHECK(rows[0].raysSaved.lower <= 2.0 + 1e-6);
    CHECK(rows[0].raysSaved.upper >= 2.0 - 1e-6);
    REQUIRE(rows[0].raysSavedFovea.estimate.Ok());
    CHECK(rows[0].raysSavedFovea.estimate.value == Approx(3.0).epsilon(1e-3));
    CHECK(rows[0].raysSavedFovea.lower <= 3.0 + 1e-6);
    CHECK(rows[0].raysSavedFovea.upper >= 3.0 - 1e-6);
    const std::string table = RaysSavedTable("uniform", rows);
    CHECK_THAT(table, Catch::Matchers::Contains("2.00×") && Catch::Matchers::Contains("3.00×"));
    // At each of its points (1, 2, 4 and 8 spp) the design scores uniform's JOD at twice its rays;
    // at 8 spp that is uniform's at 16, beyond uniform's last point, so there is nothing to read.
    REQUIRE(rows[0].raysSavedAtPoints.size() == 4);
    for (size_t i = 0; i < 3; ++i) {
        INFO("point " << i << ": " << rows[0].raysSavedAtPoints[i].estimate.reason);
        REQUIRE(rows[0].raysSavedAtPoints[i].estimate.Ok());
        CHECK(rows[0].raysSavedAtPoints[i].estimate.value == Approx(2.0).epsilon(1e-9));
        CHECK(rows[0].raysSavedAtPoints[i].lower == Approx(2.0).epsilon(1e-9));
        CHECK(rows[0].raysSavedAtPoints[i].upper == Approx(2.0).epsilon(1e-9));
    }
    CHECK_THAT(rows[0].raysSavedAtPoints[3].estimate.reason, Catch::Matchers::Contains("lies outside the anchor's"));

    const SweepPointValues values = PointValues(points[1], "room", "svgf", spec.seeds);
    CHECK(values.jod.size() == 3);
    CHECK(values.jod[1] == Approx(ClosedFormUniformJod(2.0, 2)));
    CHECK(values.tracedSpp[0] == 2.0);
}

namespace {

nlohmann::json ReadJsonFile(const fs::path& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

void WriteJsonFile(const fs::path& path, const nlohmann::json& json) { std::ofstream(path) << json.dump(2); }

// What an experiment writes beside each point of a sweep that the points of these tests, made
// without rendering, lack: the point's manifest with the content its scene loaded.
void WritePointManifests(const fs::path& run, const std::string& fingerprint) {
    const nlohmann::json manifest = ReadJsonFile(run / "manifest.json");
    for (const nlohmann::json& point : manifest["sweep"]["points"]) {
        const fs::path dir = run / "designs" / point["label"].get<std::string>();
        fs::create_directories(dir);
        WriteJsonFile(dir / "manifest.json", {{"scenes", {{{"scene", "room"}, {"fingerprint", fingerprint}}}}});
    }
}

std::string GatherError(const std::vector<fs::path>& runs, GazeWindows gaze = GazeWindows::kSame) {
    try {
        (void)GatherSweepRuns(runs, gaze);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace

TEST_CASE("rays saved from sweeps that ran apart: what one sweep gives, and runs that differ refused", "[app][designs]") {
    // The closed-form sweep above, written as two runs: run a holds uniform's four points and the
    // design's at 1 and 2 spp, run b uniform's 1 spp again and the design's at 4 and 8.
    ExperimentSpec spec = ClosedFormSpec("apart");
    spec.config.output.report = false;
    const std::vector<SweepPointResult> points = ClosedFormPoints(spec);
    std::vector<SweepPointResult> a, b;
    for (const SweepPointResult& p : points) {
        const SweepPoint& point = spec.sweep.points[p.point];
        const bool anchor = point.design == 0;
        if (anchor || *point.budgetSpp <= 2.0) a.push_back(p);
        if ((anchor && *point.budgetSpp == 1.0) || (!anchor && *point.budgetSpp >= 4.0)) b.push_back(p);
    }
    const std::vector<RaysSavedRow> whole = SweepRaysSaved(spec, points);
    REQUIRE(whole.size() == 1);
    const fs::path dir = test::ScratchDir("fovrt_rays_saved");
    for (const auto& [name, part] : {std::pair{"a", &a}, std::pair{"b", &b}}) {
        fs::create_directories(dir / name);
        WriteSweepOutputs(spec, *part, dir / name, std::chrono::steady_clock::now());
        WritePointManifests(dir / name, "00c0ffee00c0ffee");
    }

    const GatheredCurves curves = GatherSweepRuns({dir / "a", dir / "b"});
    CHECK(curves.rows.size() == 8 * 3);  // 8 points × 3 seeds: uniform's 1 spp once
    const std::vector<DesignComparison> apart = CompareDesigns(curves, "uniform", {});
    REQUIRE(apart.size() == 1);
    const DesignComparison& c = apart[0];
    CHECK(c.units == std::vector<SampleUnit>{{0, 1}, {0, 2}, {0, 3}});
    CHECK(c.budgets == std::vector<std::string>{"1", "2", "4", "8"});
    // curves.csv keeps 9 significant digits.
    REQUIRE(c.saved.raysSaved.estimate.Ok());
    CHECK(c.saved.raysSaved.estimate.value == Approx(2.0).epsilon(1e-6));
    CHECK(c.saved.raysSaved.estimate.value == Approx(whole[0].raysSaved.estimate.value).epsilon(1e-6));
    CHECK(c.saved.raysSaved.lower == Approx(whole[0].raysSaved.lower).epsilon(1e-6));
    CHECK(c.saved.raysSaved.upper == Approx(whole[0].raysSaved.upper).epsilon(1e-6));
    CHECK(c.saved.jodGain.estimate.value == Approx(0.8 * std::log(2.0)).epsilon(1e-6));
    CHECK(c.saved.raysSavedFovea.estimate.value == Approx(3.0).epsilon(1e-6));
    REQUIRE(c.saved.raysSavedAtPoints.size() == 4);
    CHECK(c.saved.raysSavedAtPoints[2].estimate.value == Approx(2.0).epsilon(1e-6));  // from run b, on run a's anchor
    CHECK_FALSE(c.saved.raysSavedAtPoints[3].estimate.Ok());                           // beyond uniform's 8 spp
    const std::string text = DesignComparisonText("uniform", apart);
    CHECK_THAT(text, Catch::Matchers::Contains("2.00× [2.00, 2.00]") && Catch::Matchers::Contains("1 2 3"));
    CHECK_THROWS_WITH(CompareDesigns(curves, "disc", {}), Catch::Matchers::Contains("anchor design 'disc'"));
    CHECK_THROWS_WITH(CompareDesigns(curves, "uniform", {"fovv"}), Catch::Matchers::Contains("design 'fovv'"));

    // Only the seeds every point holds: run c has the design's 4 and 8 spp with seed 2 alone.
    ExperimentSpec seed2 = spec;
    seed2.seeds = {2};
    fs::create_directories(dir / "c");
    WriteSweepOutputs(seed2, {b[1], b[2]}, dir / "c", std::chrono::steady_clock::now());
    WritePointManifests(dir / "c", "00c0ffee00c0ffee");
    const std::vector<DesignComparison> seedTwo =
        CompareDesigns(GatherSweepRuns({dir / "a", dir / "c"}), "uniform", {"fov"});
    REQUIRE(seedTwo.size() == 1);
    CHECK(seedTwo[0].units == std::vector<SampleUnit>{{0, 2}});
    CHECK(seedTwo[0].saved.raysSaved.estimate.value == Approx(2.0).epsilon(1e-6));

    // A point two runs hold with different scores.
    fs::copy(dir / "b", dir / "changed", fs::copy_options::recursive);
    {
        std::ifstream in(dir / "b" / "curves.csv");
        std::string csv((std::istreambuf_iterator<char>(in)), {});
        const size_t row = csv.find("room,svgf,uniform,1,1,");
        REQUIRE(row != std::string::npos);
        const size_t jod = csv.find(",7.", row);  // the row's JOD: 7 + 0.01
        csv.replace(jod, 3, ",6.");
        std::ofstream(dir / "changed" / "curves.csv") << csv;
    }
    CHECK_THAT(GatherError({dir / "a", dir / "changed"}),
               Catch::Matchers::Contains("disagree on room / svgf / design uniform at 1 spp / seed 1: jod"));
    // Another configuration.
    fs::copy(dir / "b", dir / "wider", fs::copy_options::recursive);
    nlohmann::json manifest = ReadJsonFile(dir / "b" / "manifest.json");
    manifest["config"]["camera"]["width"] = 999;
    WriteJsonFile(dir / "wider" / "manifest.json", manifest);
    CHECK_THAT(GatherError({dir / "a", dir / "wider"}), Catch::Matchers::Contains("camera.width differs"));
    // The output folder alone may differ.
    manifest = ReadJsonFile(dir / "b" / "manifest.json");
    manifest["config"]["output"]["dir"] = "elsewhere";
    WriteJsonFile(dir / "wider" / "manifest.json", manifest);
    CHECK(GatherError({dir / "a", dir / "wider"}) == "(no error)");
    // A run from a build before a key existed ran at its default, and compares with one that
    // records it; a run that set it elsewhere still differs.
    manifest = ReadJsonFile(dir / "b" / "manifest.json");
    REQUIRE(manifest["config"]["foveation"].contains("spp_cap_ratio"));
    manifest["config"]["foveation"].erase("spp_cap_ratio");
    WriteJsonFile(dir / "wider" / "manifest.json", manifest);
    CHECK(GatherError({dir / "a", dir / "wider"}) == "(no error)");
    CHECK(GatherError({dir / "wider", dir / "a"}) == "(no error)");
    manifest = ReadJsonFile(dir / "b" / "manifest.json");
    manifest["config"]["foveation"]["spp_cap_ratio"] = 4;
    WriteJsonFile(dir / "wider" / "manifest.json", manifest);
    CHECK_THAT(GatherError({dir / "a", dir / "wider"}), Catch::Matchers::Contains("foveation.spp_cap_ratio differs"));
    // One name, two designs.
    fs::copy(dir / "b", dir / "renamed", fs::copy_options::recursive);
    nlohmann::json summary = ReadJsonFile(dir / "b" / "summary.json");
    summary["designs"]["fov"]["keys"]["foveation.model"] = "disc";
    WriteJsonFile(dir / "renamed" / "summary.json", summary);
    CHECK_THAT(GatherError({dir / "a", dir / "renamed"}),
               Catch::Matchers::Contains("different designs 'fov' (foveation.model differs)"));
    // A scene whose files changed between the runs, under the same config.
    fs::copy(dir / "b", dir / "edited", fs::copy_options::recursive);
    WritePointManifests(dir / "edited", "00c0ffee00c0ffef");
    CHECK_THAT(GatherError({dir / "a", dir / "edited"}),
               Catch::Matchers::Contains("loaded different content for scene 'room' (fingerprints 00c0ffee00c0ffee and "
                                         "00c0ffee00c0ffef)"));
    // A sweep whose point lost its folder.
    fs::remove_all(dir / "edited" / "designs");
    CHECK_THAT(GatherError({dir / "a", dir / "edited"}),
               Catch::Matchers::Contains("is incomplete (its point uniform-b1 has no manifest)"));
    // Not a sweep's output.
    fs::create_directories(dir / "empty");
    CHECK_THAT(GatherError({dir / "empty"}), Catch::Matchers::Contains("manifest.json: cannot open"));
}

TEST_CASE("rays saved pooled over gaze windows: the geometric mean of equal-slope windows", "[app][designs]") {
    // Window 1 (the eye from 3 s) saves 2×, window 2 (from 9 s, 0.3 JOD higher everywhere) 4×. With
    // equal slopes the averaged curves are 0.8 ln(rays) apart by 0.8 (ln 2 + ln 4) / 2: √8 rays saved.
    ExperimentSpec spec = ClosedFormSpec("pooled");
    spec.config.output.report = false;
    const fs::path dir = test::ScratchDir("fovrt_rays_saved_pooled");
    auto write = [&](const std::string& name, double saved, double offset, double startMs) {
        fs::create_directories(dir / name);
        WriteSweepOutputs(spec, ClosedFormPoints(spec, saved, offset), dir / name, std::chrono::steady_clock::now());
        WritePointManifests(dir / name, "00c0ffee00c0ffee");
        nlohmann::json manifest = ReadJsonFile(dir / name / "manifest.json");
        manifest["config"]["gaze"]["trace_start_ms"] = startMs;
        WriteJsonFile(dir / name / "manifest.json", manifest);
    };
    write("w1", 2.0, 0.0, 3000.0);
    write("w2", 4.0, 0.3, 9000.0);
    CHECK_THAT(GatherError({dir / "w1", dir / "w2"}),
               Catch::Matchers::Contains("gaze.trace_start_ms differs") && Catch::Matchers::Contains("--pool-gaze"));

    const GatheredCurves curves = GatherSweepRuns({dir / "w1", dir / "w2"}, GazeWindows::kPooled);
    REQUIRE(curves.windows.size() == 2);
    CHECK(curves.windows[0] == "gaze.trace_start_ms=3000.0");
    CHECK(curves.windows[1] == "gaze.trace_start_ms=9000.0");
    CHECK(curves.rows.size() == 2 * 8 * 3);
    const std::vector<DesignComparison> pooled = CompareDesigns(curves, "uniform", {});
    REQUIRE(pooled.size() == 1);
    CHECK(pooled[0].units.size() == 6);
    REQUIRE(pooled[0].saved.raysSaved.estimate.Ok());
    CHECK(pooled[0].saved.raysSaved.estimate.value == Approx(std::sqrt(8.0)).epsilon(1e-6));
    // The interval spans the windows: resamples of window 1 alone give 2×, of window 2 alone 4×.
    CHECK(pooled[0].saved.raysSaved.lower < 2.6);
    CHECK(pooled[0].saved.raysSaved.upper > 3.1);
    const std::string text = DesignComparisonText("uniform", pooled, curves.windows);
    CHECK_THAT(text, Catch::Matchers::Contains("2 gaze windows pooled") &&
                         Catch::Matchers::Contains("95 % window and seed bootstrap") &&
                         Catch::Matchers::Contains("w2  gaze.trace_start_ms=9000.0") && Catch::Matchers::Contains("w2:3"));
    // Each window's own saving, beside the pooled one.
    const std::string perWindow = PerWindowText(curves, "uniform", {});
    CHECK_THAT(perWindow, Catch::Matchers::Contains("Each window alone"));
    CHECK_THAT(perWindow, Catch::Matchers::Matches("[\\s\\S]*w1 +room +[^\\n]*2\\.00× \\[2\\.00, 2\\.00\\][\\s\\S]*"));
    CHECK_THAT(perWindow, Catch::Matchers::Matches("[\\s\\S]*w2 +room +[^\\n]*4\\.00× \\[4\\.00, 4\\.00\\][\\s\\S]*"));
    CHECK(PerWindowText(GatherSweepRuns({dir / "w2"}, GazeWindows::kPooled), "uniform", {}).empty());
    // A window whose design shares no seed with its anchor: listed with the reason, the others kept.
    GatheredCurves unpaired = curves;
    for (CurveRow& row : unpaired.rows)
        if (row.window == 1 && row.design == "fov") row.seed += 100;
    const std::string partial = PerWindowText(unpaired, "uniform", {});
    CHECK_THAT(partial, Catch::Matchers::Matches("[\\s\\S]*w1 +room +[^\\n]*2\\.00× \\[2\\.00, 2\\.00\\][\\s\\S]*"));
    CHECK_THAT(partial, Catch::Matchers::Matches("[\\s\\S]*w2 +— +[^\\n]*no seed is common to every point[\\s\\S]*"));
    // The runs' order on the command line changes neither the windows' labels nor the interval.
    const GatheredCurves reversed = GatherSweepRuns({dir / "w2", dir / "w1"}, GazeWindows::kPooled);
    CHECK(reversed.windows == curves.windows);
    const std::vector<DesignComparison> pooledReversed = CompareDesigns(reversed, "uniform", {});
    REQUIRE(pooledReversed.size() == 1);
    CHECK(pooledReversed[0].saved.raysSaved.lower == pooled[0].saved.raysSaved.lower);
    CHECK(pooledReversed[0].saved.raysSaved.upper == pooled[0].saved.raysSaved.upper);
    // Nor where the windows' maps traced slightly different rays: a point's rays are its units' mean.
    GatheredCurves shifted = curves, shiftedReversed = reversed;
    for (GatheredCurves* g : {&shifted, &shiftedReversed})
        for (CurveRow& row : g->rows)
            if (row.window == 1) row.tracedWhole *= 1.005;
    CHECK(CompareDesigns(shifted, "uniform", {})[0].saved.raysSaved.estimate.value ==
          CompareDesigns(shiftedReversed, "uniform", {})[0].saved.raysSaved.estimate.value);
    // Each window alone still gives its own saving.
    CHECK(CompareDesigns(GatherSweepRuns({dir / "w2"}, GazeWindows::kPooled), "uniform", {})[0]
              .saved.raysSaved.estimate.value == Approx(4.0).epsilon(1e-6));

    // The tracker is not where the eye looks: runs behind different trackers are not pooled.
    fs::copy(dir / "w2", dir / "late", fs::copy_options::recursive);
    nlohmann::json manifest = ReadJsonFile(dir / "w2" / "manifest.json");
    manifest["config"]["gaze"]["tracker_latency_ms"] = 40.0;
    WriteJsonFile(dir / "late" / "manifest.json", manifest);
    const std::string error = GatherError({dir / "w1", dir / "late"}, GazeWindows::kPooled);
    CHECK_THAT(error, Catch::Matchers::Contains("gaze.tracker_latency_ms differs"));
    CHECK_THAT(error, !Catch::Matchers::Contains("--pool-gaze"));
}

TEST_CASE("rays saved on the budgets runs share: --budget keeps those points", "[app][designs]") {
    // The closed-form sweep (both designs at 1, 2, 4 and 8 spp, seeds 1–3) kept to 1, 2 and 4 spp:
    // 8 spp drops out of both curves, every seed stays, and the saving is still exactly 2.
    ExperimentSpec spec = ClosedFormSpec("budgets");
    spec.config.output.report = false;
    const std::vector<SweepPointResult> points = ClosedFormPoints(spec);
    const fs::path dir = test::ScratchDir("fovrt_rays_saved_budgets");
    fs::create_directories(dir / "a");
    WriteSweepOutputs(spec, points, dir / "a", std::chrono::steady_clock::now());
    WritePointManifests(dir / "a", "00c0ffee00c0ffee");
    GatheredCurves curves = GatherSweepRuns({dir / "a"});
    KeepBudgets(curves, {1.0, 2.0, 4.0});
    CHECK(curves.rows.size() == 6 * 3);
    const std::vector<DesignComparison> kept = CompareDesigns(curves, "uniform", {});
    REQUIRE(kept.size() == 1);
    CHECK(kept[0].budgets == std::vector<std::string>{"1", "2", "4"});
    CHECK(kept[0].units.size() == 3);
    CHECK(kept[0].saved.raysSaved.estimate.value == Approx(2.0).epsilon(1e-6));
    CHECK_THROWS_WITH(KeepBudgets(curves, {3.0}), Catch::Matchers::Contains("--budget 3: no run holds a point at 3 spp"));
}
