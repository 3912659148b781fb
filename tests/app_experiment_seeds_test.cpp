// Seeds (issue #16): each run seed is a full pass with its own noise, while the reference has its
// own fixed seed (reference.seed) and is shared by every run seed.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/experiment.h"
#include "app_test_configs.h"
#include "config/config_cli.h"
#include "core/error.h"
#include "pipeline/frame_pipeline.h"
#include "pipeline/reference_cache.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;
using fovrt::test::ReadFile;

namespace {

bool SamePixels(const Plane<vec3>& a, const Plane<vec3>& b) {
    if (a.width() != b.width() || a.height() != b.height()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i] != b[i]) return false;
    return true;
}

std::string ErrorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("two seeds give different noisy inputs and identical references", "[app][seeds]") {
    const fs::path dir = test::ScratchDir("fovrt_seeds_test");
    RunConfig config = test::SmallCornellConfig();
    config.reference.spp = 4;
    std::vector<Plane<vec3>> noisy, references;
    std::vector<std::string> keys;
    for (uint32_t seed : {1u, 2u}) {
        config.run.seed = seed;
        FramePipeline pipeline(config);
        StereoFrame frame;
        pipeline.Render(0, frame);
        noisy.push_back(frame.eyes[0].inputs.NoisyImage());
        // Each seed renders its reference into its own cache: nothing is shared but the key.
        ReferenceCache cache(dir / fmt::format("cache{}", seed));
        ReferenceKey key = MakeReferenceKey(pipeline.GetScene(), SceneFingerprint(pipeline.GetScene()), 0,
                                            frame.timeSeconds, 0, frame.eyes[0].camera, config.reference.spp,
                                            config.run.maxDepth, config.reference.seed);
        bool hit = true;
        references.push_back(cache.GetOrRender(key, pipeline.GetRenderer(), &hit));
        CHECK_FALSE(hit);
        keys.push_back(key.Hex());
    }
    CHECK_FALSE(SamePixels(noisy[0], noisy[1]));
    CHECK(SamePixels(references[0], references[1]));
    CHECK(keys[0] == keys[1]);
    // The reference's own seed does change it.
    config.reference.seed = 2;
    FramePipeline pipeline(config);
    StereoFrame frame;
    pipeline.Render(0, frame);
    Plane<vec3> other;
    pipeline.GetRenderer().RenderReference(0, frame.eyes[0].camera, config.reference.spp, HashCombine(2u, 0u), other);
    CHECK_FALSE(SamePixels(other, references[0]));
}

TEST_CASE("experiment over seeds: every value in the CSV with its seed, one shared reference per eye",
          "[app][seeds]") {
    const fs::path dir = test::ScratchDir("fovrt_seeds_test") / "experiment";
    const ConfigOptions options =
        test::SmallExperimentOptions(dir, {.experimentLines = "baseline = \"two-history\"\nseeds = [4, 9]\n"});
    ExperimentSpec spec = LoadExperiment(options);
    CHECK(spec.seeds == std::vector<uint32_t>{4, 9});
    CHECK(spec.baseline == "two-history");
    Results results = RunExperiment(spec);
    CHECK(results.Seeds("cornell") == std::vector<uint32_t>{4, 9});

    // Per seed the same (frame, eye, variant, region, metric) cells, with different values.
    std::map<std::tuple<int, int, std::string, std::string, std::string>, std::map<uint32_t, double>> cells;
    for (const ResultRow& r : results.rows()) cells[{r.frame, r.eye, r.variant, r.region, r.metric}][r.seed] = r.value;
    int differ = 0;
    for (const auto& [cell, bySeed] : cells) {
        REQUIRE(bySeed.size() == 2u);
        differ += bySeed.at(4) != bySeed.at(9) ? 1 : 0;
    }
    CHECK(differ > int(cells.size()) / 2);
    const std::string csv = ReadFile(dir / "out" / "frames-cornell.csv");
    CHECK(csv.rfind("seed,frame,eye,variant,region,metric,value\n", 0) == 0);
    CHECK(csv.find("\n9,2,1,two-history,fovea,relmse,") != std::string::npos);
    CHECK(size_t(std::count(csv.begin(), csv.end(), '\n')) == 1 + results.rows().size());

    // The static Cornell box: one reference per eye, rendered once, read by every seed and frame.
    size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir / "cache")) ++entries;
    CHECK(entries == 2u);
    nlohmann::json manifest = nlohmann::json::parse(ReadFile(dir / "out" / "manifest.json"));
    CHECK(manifest["seeds"] == nlohmann::json::array({4, 9}));
    CHECK(manifest["baseline"] == "two-history");
    CHECK(manifest["scenes"][0]["reference_lookups"] == 12);  // 2 seeds × 3 frames × 2 eyes
    CHECK(manifest["scenes"][0]["reference_cache_hits"] == 10);

    nlohmann::json summary = nlohmann::json::parse(ReadFile(dir / "out" / "summary.json"));
    auto& vs = summary["scenes"]["cornell"]["variants"]["svgf"]["whole"]["relmse"]["vs_baseline"];
    CHECK(vs["pairs"] == 12);
    CHECK(vs["ci_low"].get<double>() <= vs["ratio"].get<double>());
    CHECK(vs["ratio"].get<double>() <= vs["ci_high"].get<double>());

    // A seed's values do not depend on the seeds run before it (the denoisers are reset between
    // seeds): seed 9 alone gives the same values as seed 9 after seed 4.
    ExperimentSpec alone = spec;
    alone.seeds = {9};
    alone.config.output.dir = (dir / "out9").string();
    Results nine = RunExperiment(alone);
    size_t compared = 0;
    for (const ResultRow& r : nine.rows()) {
        REQUIRE(cells.count({r.frame, r.eye, r.variant, r.region, r.metric}) == 1u);
        CHECK(cells.at({r.frame, r.eye, r.variant, r.region, r.metric}).at(9) == r.value);
        ++compared;
    }
    CHECK(compared * 2 == results.rows().size());

    // --seeds replaces the file's list: N seeds from run.seed, or a list.
    ExperimentArgs args;
    args.seeds = "3";
    CHECK(LoadExperiment(options, args).seeds == std::vector<uint32_t>{1, 2, 3});
    args.seeds = "7,5";
    CHECK(LoadExperiment(options, args).seeds == std::vector<uint32_t>{7, 5});
}

TEST_CASE("bad seeds and baselines are one line naming the option or key", "[app][seeds]") {
    CHECK(ParseSeedsOption("2", 10) == std::vector<uint32_t>{10, 11});
    CHECK(ErrorOf([] { ParseSeedsOption("x", 1); }).find("--seeds x: 'x' is not a non-negative integer") == 0);
    CHECK(ErrorOf([] { ParseSeedsOption("0", 1); }).find("--seeds 0: the count must be in [1, 1000]") == 0);
    CHECK(ErrorOf([] { ParseSeedsOption("1,,2", 1); }).find("--seeds 1,,2: '' is not") == 0);
    CHECK(ErrorOf([] { ParseSeedsOption("3,3", 1); }).find("seed 3 is listed twice") != std::string::npos);
    CHECK(ErrorOf([] { ParseSeedsOption("4294967296", 1); }).find("above 2^32 - 1") != std::string::npos);

    const fs::path dir = test::ScratchDir("fovrt_seeds_test") / "bad";
    auto errorFor = [&](const std::string& experimentLines) {
        const ConfigOptions options = test::ExperimentFileOptions(
            dir, "[experiment]\nscenes = [\"cornell\"]\nvariants = [\"svgf\", \"asvgf\"]\n" + experimentLines);
        return ErrorOf([&] { LoadExperiment(options); });
    };
    CHECK(errorFor("seeds = 3\n").find("experiment.seeds must be a non-empty array") != std::string::npos);
    CHECK(errorFor("seeds = []\n").find("experiment.seeds must be a non-empty array") != std::string::npos);
    CHECK(errorFor("seeds = [1.5]\n").find("experiment.seeds must hold only integers") != std::string::npos);
    CHECK(errorFor("seeds = [-1]\n").find("experiment.seeds must hold only integers") != std::string::npos);
    CHECK(errorFor("seeds = [2, 2]\n").find("experiment.seeds lists seed 2 twice") != std::string::npos);
    CHECK(errorFor("baseline = \"asvg\"\n").find("experiment.baseline 'asvg' is not in experiment.variants (did "
                                                 "you mean 'asvgf'?)") != std::string::npos);
    CHECK(errorFor("seed = [1]\n").find("unknown key experiment.seed (did you mean experiment.seeds?)") !=
          std::string::npos);
    CHECK(errorFor("").empty());
}

TEST_CASE("--set experiment.KEY acts exactly like the key in the file", "[app][config]") {
    ConfigOptions options = test::ExperimentFileOptions(
        test::ScratchDir("fovrt_seeds_test") / "set",
        "[experiment]\nscenes = [\"cornell\"]\nvariants = [\"svgf\", \"asvgf\"]\n[experiment.quick.run]\nframes = 2\n");
    options.sets = {"experiment.variants=[\"two-history\", \"svgf\"]", "experiment.seeds=[4, 9]",
                    "experiment.scenes=[\"veach-ajar\"]", "experiment.baseline=\"svgf\"", "experiment.visual_frame=1"};
    ExperimentSpec spec = LoadExperiment(options);
    CHECK(spec.variants == std::vector<std::string>{"two-history", "svgf"});
    CHECK(spec.config.denoise.denoisers == spec.variants);
    CHECK(spec.seeds == std::vector<uint32_t>{4, 9});
    CHECK(spec.scenes == std::vector<std::string>{"veach-ajar"});
    CHECK(spec.baseline == "svgf");
    CHECK(spec.visualFrame == 1);

    // A key inside [experiment.quick] is merged by --quick like the file's own.
    options.sets = {"experiment.quick.run.frames=3"};
    ExperimentArgs quick;
    quick.quick = true;
    CHECK(LoadExperiment(options, quick).config.run.frames == 3);

    // Unknown and bad keys are refused naming the --set they came from; file keys name file:line.
    options.sets = {"experiment.bogus=1"};
    const std::string unknown = ErrorOf([&] { LoadExperiment(options); });
    CHECK(unknown.find("--set experiment.bogus=1: unknown key experiment.bogus (did you mean experiment.") == 0);
    options.sets = {"experiment.seed=[1]"};
    CHECK(ErrorOf([&] { LoadExperiment(options); }).find("did you mean experiment.seeds?") != std::string::npos);
    options.sets = {"experiment.seeds=[2, 2]"};
    CHECK(ErrorOf([&] { LoadExperiment(options); }).find("--set experiment.seeds=[2, 2]: experiment.seeds lists seed 2 twice") == 0);
    options.sets = {"experiment.variants=[\"svgff\"]"};
    CHECK(ErrorOf([&] { LoadExperiment(options); }).find("svgf") != std::string::npos);
    options.sets = {"experiment.baseline=\"nope\""};
    CHECK(ErrorOf([&] { LoadExperiment(options); }).find("--set experiment.baseline=\"nope\": experiment.baseline 'nope'") == 0);
    options.sets = {};
    std::ofstream(options.configPath, std::ios::app) << "[experiment.extra]\n";
    CHECK(ErrorOf([&] { LoadExperiment(options); }).find(options.configPath + ":6: unknown key experiment.extra") == 0);
}
