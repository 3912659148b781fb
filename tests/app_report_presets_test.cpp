// The experiment presets in presets/: every key is a valid RunConfig key (the config loader
// rejects unknown keys), the [experiment] table names scenes and known denoisers, the thesis
// protocol values are what SPEC §5 says, and the [experiment.quick] overrides shrink the run.
#include <filesystem>
#include <sstream>

#include <toml++/toml.h>

#include "pipeline/frame_pipeline.h"
#include "config/config.h"
#include "config/config_io.h"
#include "denoise/denoiser.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace fovrt;

namespace {

// Deep-merges `over` into `base` (tables recursively, other values replaced).
void Merge(toml::table& base, const toml::table& over) {
    for (const auto& [key, node] : over) {
        if (const toml::table* sub = node.as_table(); sub && base[key].as_table()) {
            Merge(*base[key].as_table(), *sub);
        } else {
            base.insert_or_assign(key, node);
        }
    }
}

struct Preset {
    RunConfig config;
    RunConfig quick;
    std::vector<std::string> scenes, variants;
};

Preset LoadPreset(const std::string& name) {
    const auto path = test::SourceDir() / "presets" / name;
    REQUIRE(std::filesystem::exists(path));
    toml::table file = toml::parse_file(path.string());
    REQUIRE(file["experiment"].as_table());
    toml::table experiment = *file["experiment"].as_table();
    file.erase("experiment");
    Preset p;
    for (const auto& v : *experiment["scenes"].as_array()) p.scenes.push_back(*v.value<std::string>());
    for (const auto& v : *experiment["variants"].as_array()) p.variants.push_back(*v.value<std::string>());
    std::ostringstream text;
    text << file;
    p.config = ConfigFromTomlString(text.str(), name);
    REQUIRE(experiment["quick"].as_table());
    Merge(file, *experiment["quick"].as_table());
    std::ostringstream quickText;
    quickText << file;
    p.quick = ConfigFromTomlString(quickText.str(), name + " [quick]");
    return p;
}

void CheckCommon(const Preset& p) {
    for (const std::string& v : p.variants) CHECK(LookupDenoiserVariant(v) != nullptr);  // suffixes too
    for (const std::string& s : p.scenes)
        CHECK(std::filesystem::exists(test::SourceDir() / "scenes" / (s + ".toml")));
    CHECK(p.quick.camera.width < p.config.camera.width);
    CHECK(p.quick.run.frames < p.config.run.frames);
    CHECK(p.quick.reference.spp < p.config.reference.spp);
    CHECK(p.quick.reference.spp >= 1);
}

// The thesis's foveation (an 8/1 spp disc of 200 px at 1280 wide) and its two a-trous iterations.
void CheckThesisFoveation(const RunConfig& c) {
    CHECK(c.camera.width == 1280);
    CHECK(c.foveation.model == "disc");
    CHECK(c.foveation.sppInside == 8);
    CHECK(c.foveation.sppOutside == 1);
    CHECK(c.foveation.radiusPx == 200.0f);
    CHECK(c.denoise.params.svgf.atrousIterations == 2);
}

}  // namespace

TEST_CASE("thesis-foveated preset: the thesis protocol", "[app][presets]") {
    Preset p = LoadPreset("thesis-foveated.toml");
    CheckCommon(p);
    CHECK(p.scenes == std::vector<std::string>{"cornell", "veach-ajar"});
    CHECK(p.variants == std::vector<std::string>{"svgf", "svgf-weighted", "two-history", "asvgf", "two-history-asvgf"});
    const RunConfig& c = p.config;
    CheckThesisFoveation(c);
    CHECK(c.camera.height == 720);
    CHECK(c.denoise.params.svgf.feedbackIteration == 1);
    CHECK(c.denoise.params.svgf.alphaColor == Approx(0.05f));
    CHECK(c.denoise.params.twoHistory.gradientBeta == Approx(0.8f));
    CHECK(c.gaze.source == "lissajous");
    CHECK(c.gaze.amplitude.x == 640.0f);
    CHECK(c.gaze.frequencyHz.y == Approx(0.5f));
    CHECK(c.gaze.phaseDeg.x == Approx(90.0f));
    CHECK(p.quick.camera.width * 9 == p.quick.camera.height * 16);  // keeps 16:9
}

TEST_CASE("svgf-paper preset: uniform 1 spp, 5 iterations, α = 0.2", "[app][presets]") {
    Preset p = LoadPreset("svgf-paper.toml");
    CheckCommon(p);
    CHECK(p.config.foveation.model == "uniform");
    CHECK(p.config.foveation.uniformSpp == 1);
    CHECK(p.config.denoise.params.svgf.atrousIterations == 5);
    CHECK(p.config.denoise.params.svgf.alphaColor == Approx(0.2f));
}

TEST_CASE("asvgf-lag preset: room and pillars, svgf vs asvgf vs asvgf-antilag", "[app][presets]") {
    Preset p = LoadPreset("asvgf-lag.toml");
    CheckCommon(p);
    CHECK(p.scenes == std::vector<std::string>{"room", "pillars"});
    CHECK(p.variants == std::vector<std::string>{"svgf", "asvgf", "asvgf-antilag"});
    CHECK(p.config.denoise.params.asvgf.alpha == Approx(0.1f));
}

namespace {

// Which lights and emitters are on at `time`: a switch is a change of this between two frames.
std::vector<bool> LitAt(const Scene& scene, double time) {
    SceneState state = scene.StateAt(float(time));
    std::vector<bool> lit;
    for (float scale : state.emissionScale) lit.push_back(scale > 0.0f);
    for (const LightState& light : state.lights) lit.push_back(light.radiantIntensity.x + light.radiantIntensity.y +
                                                                light.radiantIntensity.z > 0.0f);
    return lit;
}

// The frames (of run.first_frame .. + run.frames) of `config` in the room scene lit differently
// from the frame before, at the times the frame pipeline gives them.
std::vector<int> SwitchFrames(RunConfig config) {
    config.scene.name = (test::SourceDir() / "scenes" / "room.toml").string();
    const FramePipeline pipeline(config);
    const RunSettings& run = config.run;
    std::vector<int> frames;
    for (int f = run.firstFrame + 1; f < run.firstFrame + run.frames; ++f)
        if (LitAt(pipeline.GetScene(), pipeline.TimeOf(uint32_t(f))) !=
            LitAt(pipeline.GetScene(), pipeline.TimeOf(uint32_t(f - 1))))
            frames.push_back(f);
    return frames;
}

}  // namespace

TEST_CASE("asvgf-lag preset: the quick run covers a light switch in room, with frames either side", "[app][presets]") {
    Preset p = LoadPreset("asvgf-lag.toml");
    const std::vector<int> full = SwitchFrames(p.config);
    REQUIRE(!full.empty());
    const std::vector<int> quick = SwitchFrames(p.quick);
    INFO("quick frames " << p.quick.run.firstFrame << " + " << p.quick.run.frames << ", first switch of the full run at frame "
                         << full.front());
    REQUIRE(!quick.empty());
    // Lag is measured after the switch, against histories built before it: a few frames of each.
    CHECK(quick.front() - p.quick.run.firstFrame >= 4);
    CHECK(p.quick.run.firstFrame + p.quick.run.frames - quick.front() >= 4);
    CHECK(p.quick.run.frames <= 16);  // still quick
}

TEST_CASE("brdf-demodulation preset: albedo vs F_beta for svgf and two-history, thesis foveation", "[app][presets]") {
    Preset p = LoadPreset("brdf-demodulation.toml");
    CheckCommon(p);
    CHECK(p.scenes == std::vector<std::string>{"brdf-detail", "brdf-detail-moving", "cornell", "veach-ajar"});
    CHECK(p.variants == std::vector<std::string>{"svgf", "svgf+brdf", "two-history", "two-history+brdf"});
    const RunConfig& c = p.config;
    CHECK(c.render.demodulation == "albedo");  // one render feeds both kinds of variant
    CheckThesisFoveation(c);
}

TEST_CASE("every preset runs three seeds", "[app][presets]") {
    for (const char* name : {"thesis-foveated.toml", "svgf-paper.toml", "asvgf-lag.toml", "quickstart.toml"}) {
        INFO(name);
        toml::table file = toml::parse_file((test::SourceDir() / "presets" / name).string());
        const toml::array* seeds = file["experiment"]["seeds"].as_array();
        REQUIRE(seeds);
        CHECK(seeds->size() >= 3u);
    }
}

TEST_CASE("quickstart preset: the first command compares two denoisers on built-in data", "[app][presets]") {
    const auto path = test::SourceDir() / "presets" / "quickstart.toml";
    toml::table file = toml::parse_file(path.string());
    toml::table experiment = *file["experiment"].as_table();
    file.erase("experiment");
    std::ostringstream text;
    text << file;
    RunConfig c = ConfigFromTomlString(text.str(), "quickstart.toml");
    for (const auto& s : *experiment["scenes"].as_array())
        CHECK(std::filesystem::exists(test::SourceDir() / "scenes" / (*s.value<std::string>() + ".toml")));
    CHECK(experiment["variants"].as_array()->size() >= 2u);  // a baseline and a variant: intervals
    CHECK(c.foveation.model == "disc");
    CHECK(c.output.report);
    // Small enough to take about as long as the default `fovrt run` (docs/performance.md: The first command).
    CHECK(int64_t(c.camera.width) * c.camera.height * c.run.frames * 3 <=
          int64_t(DefaultConfig().camera.width) * DefaultConfig().camera.height * DefaultConfig().run.frames);
}
