// The experiment reports the sampling it measured (summary.json "traced_spp", the manifest's scene
// record): the path samples the tracer took per pixel, whole image, fovea and periphery at the
// true gaze, counted from FrameInputs::sampleCount, not read off the configured spp map.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "app/experiment.h"
#include "app_test_configs.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;
using fovrt::test::ReadFile;

namespace {

// The small Cornell experiment with svgf alone, 2 frames, `sets` on top; its traced_spp.
nlohmann::json TracedSpp(const fs::path& dir, std::vector<std::string> sets) {
    ConfigOptions options = test::SmallExperimentOptions(dir, {.frames = 2, .experimentLines = ""});
    options.sets = std::move(sets);
    options.sets.push_back("experiment.variants=[\"svgf\"]");
    ExperimentSpec spec = LoadExperiment(options);
    spec.config.metric.vdp = false;
    RunExperiment(spec);
    const nlohmann::json summary = nlohmann::json::parse(ReadFile(dir / "out" / "summary.json"));
    const nlohmann::json manifest = nlohmann::json::parse(ReadFile(dir / "out" / "manifest.json"));
    CHECK(manifest["scenes"][0]["traced_spp"] == summary["traced_spp"]["cornell"]);
    return summary["traced_spp"]["cornell"];
}

}  // namespace

TEST_CASE("the thesis disc measures 8 samples per pixel in the fovea and 1 outside", "[app][traced]") {
    // SmallExperimentOptions' disc: 8 spp within 8 px of the gaze (80 px at 320 wide), 1 outside; the
    // metric's fovea is that disc, so its pixels are exactly the 8-spp ones.
    const fs::path dir = test::ScratchDir("fovrt_traced") / "disc";
    const nlohmann::json spp = TracedSpp(dir, {"output.report=true"});
    CHECK(spp["fovea"].get<double>() == 8.0);
    // The report's run table shows it too.
    CHECK(ReadFile(dir / "out" / "report.html").find(" / 8.00 / 1.00") != std::string::npos);
    CHECK(spp["periphery"].get<double>() == 1.0);
    const double whole = spp["whole"].get<double>();
    CHECK(whole > 1.0);
    CHECK(whole < 8.0);
}

TEST_CASE("uniform sampling measures its spp in every region", "[app][traced]") {
    const nlohmann::json spp =
        TracedSpp(test::ScratchDir("fovrt_traced") / "uniform", {"foveation.model=uniform", "foveation.uniform_spp=3"});
    for (const char* region : {"whole", "fovea", "periphery"}) {
        INFO(region);
        CHECK(spp[region].get<double>() == 3.0);
    }
}
