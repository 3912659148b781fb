// RunConfig: defaults, TOML load, --set overrides, unknown keys, bad values, JSON/TOML round trip.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <type_traits>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "pipeline/frame_pipeline.h"
#include "config/config.h"
#include "config/config_cli.h"
#include "config/config_io.h"
#include "config/settings_tables.h"
#include "core/error.h"
#include "gaze/tracker.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;

namespace {

struct TempFile {
    fs::path path;
    TempFile(const std::string& name, const std::string& text) {
        path = fs::temp_directory_path() / fmt::format("fovrt_config_test_{}_{}", ::getpid(), name);
        std::ofstream(path) << text;
    }
    ~TempFile() { fs::remove(path); }
};

RunConfig Resolve(const std::string& file, std::vector<std::string> sets, std::string memory = "") {
    ConfigOptions options;
    options.configPath = file;
    options.sets = std::move(sets);
    options.memoryBudget = std::move(memory);
    return ResolveConfig(options);
}

}  // namespace

TEST_CASE("Defaults: the default job needs no config file", "[config]") {
    RunConfig c = Resolve("", {});
    CHECK(c.scene.name == "cornell");
    CHECK(c.camera.width == 640);
    CHECK(c.camera.height == 360);
    CHECK(!c.camera.fovDeg);
    CHECK(c.camera.ipd == 0.063f);
    CHECK(c.foveation.model == "disc");
    CHECK(c.foveation.sppInside == 8);
    CHECK(c.foveation.sppOutside == 1);
    CHECK(c.foveation.radiusPx == 200.0f);
    CHECK(c.foveation.radiusReferenceWidth == 1280);
    CHECK(c.gaze.source == "lissajous");
    CHECK(c.gaze.amplitude == vec2(640, 360));
    CHECK(c.gaze.frequencyHz == vec2(0.4f, 0.5f));
    CHECK(c.gaze.phaseDeg == vec2(90, 0));
    CHECK(c.denoise.denoisers == std::vector<std::string>{"svgf"});
    CHECK(c.denoise.device == "auto");
    CHECK(c.denoise.params.precision == Precision::Auto);  // fp16 on a GPU, fp32 on lavapipe (ResolvePrecision)
    CHECK(c.denoise.params.svgf.alphaColor == 0.2f);
    CHECK(c.memoryBudget == 0);
    CHECK(ConfigToJson(DefaultConfig()) == ConfigToJson(c));
}

TEST_CASE("TOML file, then --set overrides, then --memory-budget", "[config]") {
    TempFile file("a.toml", R"(
memory_budget = "1GiB"
[scene]
name = "veach-ajar"
[camera]
width = 1280
height = 720
fov_deg = [-50, 45, 40, -35.5]
[foveation]
model = "linear"
spp_max = 12
[gaze]
source = "static"
yaw_deg = 5
[denoise]
denoisers = ["svgf", "two-history"]
precision = "fp16"
[denoise.svgf]
atrous_iterations = 2
[denoise.two_history]
q_scale = 2.5
)");
    RunConfig c = Resolve(file.path.string(), {});
    CHECK(c.scene.name == "veach-ajar");
    CHECK(c.camera.width == 1280);
    REQUIRE(c.camera.fovDeg);
    CHECK((*c.camera.fovDeg)[3] == -35.5f);
    CHECK(c.foveation.model == "linear");
    CHECK(c.foveation.sppMax == 12);
    CHECK(c.gaze.source == "static");
    CHECK(c.gaze.yawDeg == 5.0f);
    CHECK(c.denoise.denoisers.size() == 2);
    CHECK(c.denoise.params.precision == Precision::Fp16);
    CHECK(c.denoise.params.svgf.atrousIterations == 2);
    CHECK(c.denoise.params.svgf.feedbackIteration == 1);  // untouched default
    CHECK(c.denoise.params.twoHistory.qScale == 2.5f);
    CHECK(c.memoryBudget == (1ull << 30));

    // --set wins over the file; values are TOML, bare words become strings.
    c = Resolve(file.path.string(), {"camera.width=320", "scene.name=cornell-box", "gaze.amplitude=[10, 20.5]",
                                     "denoise.svgf.filter_combined=true", "output.dir=/tmp/x y",
                                     "foveation.model=\"disc\"", "camera.width=333"});
    CHECK(c.camera.width == 333);  // applied in order
    CHECK(c.camera.height == 720);
    CHECK(c.scene.name == "cornell-box");
    CHECK(c.gaze.amplitude == vec2(10.0f, 20.5f));
    CHECK(c.denoise.params.svgf.filterCombined);
    CHECK(c.output.dir == "/tmp/x y");
    CHECK(c.foveation.model == "disc");
    // New sections through --set alone, and the memory-budget option over both.
    c = Resolve("", {"reference.spp=4096", "memory_budget=100"}, "512MiB");
    CHECK(c.reference.spp == 4096);
    CHECK(c.memoryBudget == 512ull << 20);
    CHECK(Resolve("", {}, "2GB").memoryBudget == 2000000000ull);
    CHECK(Resolve("", {}, "12345").memoryBudget == 12345ull);
}

TEST_CASE("Unknown keys are errors naming the key and the file", "[config]") {
    TempFile file("typo.toml", "[camera]\nwidth = 320\n\n[foveation]\nradus_px = 100\n");
    CHECK_THROWS_WITH(Resolve(file.path.string(), {}),
                      Catch::Contains("unknown config key 'foveation.radus_px'") &&
                          Catch::Contains("typo.toml:5"));
    TempFile section("section.toml", "[fovea]\nradius = 3\n");
    CHECK_THROWS_WITH(Resolve(section.path.string(), {}),
                      Catch::Contains("unknown config key 'fovea'") && Catch::Contains("section.toml:1"));
    CHECK_THROWS_WITH(Resolve("", {"camera.widht=3"}),
                      Catch::Contains("unknown config key 'camera.widht'") && Catch::Contains("--set"));
    CHECK_THROWS_WITH(Resolve("", {"denoise.svgf.alpha=0.1"}), Catch::Contains("'denoise.svgf.alpha'"));
    CHECK_THROWS_WITH(Resolve("", {"top_level_typo=1"}), Catch::Contains("'top_level_typo'"));
    // Warm-up frames precede the first scored frame, so there must be room for them.
    CHECK_THROWS_WITH(Resolve("", {"run.warmup_frames=3", "run.first_frame=2"}),
                      Catch::Contains("run.warmup_frames") && Catch::Contains("run.first_frame = 2"));
    CHECK(Resolve("", {"run.warmup_frames=3", "run.first_frame=3"}).run.warmupFrames == 3);
    // A known variant with a suffix its family refuses is refused here, before any rendering.
    CHECK_THROWS_WITH(Resolve("", {"denoise.denoisers=[\"rae+brdf\"]"}),
                      Catch::Contains("denoise.denoisers") && Catch::Contains("albedo-demodulated"));
    CHECK(Resolve("", {"denoise.denoisers=[\"rae+albedo\", \"svgf+brdf\"]"}).denoise.denoisers.size() == 2);
    // A composition in any order; two spellings of one denoiser are refused, naming both.
    CHECK(Resolve("", {"denoise.denoisers=[\"clamp+two-history\", \"two-history+stabilize+brdf\"]"})
              .denoise.denoisers.size() == 2);
    CHECK_THROWS_WITH(Resolve("", {"denoise.denoisers=[\"two-history-stable\", \"stabilize+two-history\"]"}),
                      Catch::Contains("'two-history-stable' and 'stabilize+two-history' are the same denoiser "
                                      "(two-history+stabilize)"));
    CHECK_THROWS_WITH(Resolve("", {"denoise.denoisers=[\"two-history+antilag\"]"}),
                      Catch::Contains("denoise.denoisers") && Catch::Contains("antilag requires asvgf"));
}

TEST_CASE("Wrong types and out-of-range values name the key", "[config]") {
    auto fails = [](std::vector<std::string> sets, const std::string& key) {
        INFO("sets: " << sets[0]);
        CHECK_THROWS_WITH(Resolve("", sets), Catch::Contains("'" + key + "'"));
        CHECK_THROWS_AS(Resolve("", sets), Error);
    };
    fails({"camera.width=0"}, "camera.width");
    fails({"camera.height=-720"}, "camera.height");
    fails({"camera.width=64.5"}, "camera.width");
    fails({"camera.width=\"wide\""}, "camera.width");
    fails({"camera.fov_deg=[10, -10, 30, -30]"}, "camera.fov_deg");
    fails({"camera.fov_deg=[1, 2, 3]"}, "camera.fov_deg");
    fails({"reference.spp=0"}, "reference.spp");
    fails({"run.frames=0"}, "run.frames");
    fails({"run.fps=-1"}, "run.fps");
    fails({"foveation.spp_inside=65"}, "foveation.spp_inside");  // past kMaxSpp
    fails({"foveation.spp_cap=65"}, "foveation.spp_cap");
    fails({"foveation.model=gaussian"}, "foveation.model");
    fails({"foveation.peripheral_deg=1"}, "foveation.peripheral_deg");
    fails({"foveation.ray_budget=10"}, "foveation.ray_budget");
    fails({"foveation.spp_outside=0.05"}, "foveation.spp_outside");  // below 1/16
    fails({"foveation.spp_floor=1.5"}, "foveation.spp_floor");
    // A budget below W·H (640×360 by default) needs a floor below 1 that lets the map reach it.
    fails({"foveation.ray_budget=115200"}, "foveation.ray_budget");
    fails({"foveation.ray_budget=50000", "foveation.spp_floor=0.25"}, "foveation.ray_budget");
    CHECK(Resolve("", {"foveation.ray_budget=57600", "foveation.spp_floor=0.25"}).foveation.rayBudget == 57600);
    // Above 16 spp on average needs a raised cap (230400 pixels).
    fails({"foveation.ray_budget=3916800"}, "foveation.ray_budget");
    CHECK(Resolve("", {"foveation.ray_budget=3916800", "foveation.spp_cap=32"}).foveation.sppCap == 32);
    // ... except for the uniform model, which has no peak for the cap to bound.
    CHECK(Resolve("", {"foveation.model=uniform", "foveation.ray_budget=3916800"}).foveation.rayBudget == 3916800);
    // ... up to 64 spp: 65 × 230400 is refused, naming the uniform model's most.
    fails({"foveation.model=uniform", "foveation.ray_budget=14976000"}, "foveation.ray_budget");
    CHECK_THROWS_WITH(Resolve("", {"foveation.model=uniform", "foveation.ray_budget=14976000"}),
                      Catch::Contains("the uniform model's most, 64 spp"));
    // ... or a cap that follows the budget: 17 spp × 4 passes 64, so the cap is 64.
    CHECK(Resolve("", {"foveation.ray_budget=3916800", "foveation.spp_cap_ratio=4"}).foveation.sppCapRatio == 4);
    fails({"foveation.spp_cap_ratio=0.5"}, "foveation.spp_cap_ratio");
    fails({"foveation.spp_cap_ratio=65"}, "foveation.spp_cap_ratio");
    CHECK(Resolve("", {"foveation.spp_outside=0.25"}).foveation.sppOutside == 0.25f);
    fails({"gaze.source=eyelink"}, "gaze.source");
    fails({"gaze.source=trace"}, "gaze.trace_path");
    fails({"denoise.precision=fp64"}, "denoise.precision");
    fails({"denoise.device=gpu0"}, "denoise.device");
    fails({"denoise.svgf.alpha_color=0"}, "denoise.svgf.alpha_color");
    fails({"denoise.svgf.feedback_iteration=6"}, "denoise.svgf.feedback_iteration");
    fails({"output.write_exr=1"}, "output.write_exr");
    fails({"memory_budget=-1"}, "memory_budget");
    fails({"memory_budget=\"12 parsecs\""}, "memory_budget");
    fails({"camera=3", "camera.width=3"}, "camera");
    // Range errors from a file carry file:line.
    TempFile file("range.toml", "[camera]\nwidth = 0\n");
    CHECK_THROWS_WITH(Resolve(file.path.string(), {}), Catch::Contains("range.toml:2"));
    // Malformed TOML and missing files: one line naming the file.
    TempFile bad("bad.toml", "[camera\nwidth = 1\n");
    CHECK_THROWS_WITH(Resolve(bad.path.string(), {}), Catch::Contains("bad.toml:1"));
    CHECK_THROWS_WITH(Resolve("/nonexistent/x.toml", {}), Catch::Contains("/nonexistent/x.toml"));
    CHECK_THROWS_WITH(Resolve("", {"noequals"}), Catch::Contains("noequals"));
    CHECK_THROWS_WITH(Resolve("", {}, "lots"), Catch::Contains("--memory-budget"));
}

TEST_CASE("ToJson / ToToml round trip", "[config]") {
    RunConfig c = Resolve("", {"camera.fov_deg=[-47.5, 41.25, 40, -38]", "camera.ipd=0.0655",
                               "foveation.model=acuity", "foveation.ray_budget=400000", "gaze.units=deg",
                               "gaze.amplitude=[12.5, 7]", "gaze.trace_path=/a/b.csv", "run.seed=4000000000",
                               "denoise.denoisers=[\"svgf\", \"asvgf\", \"two-history\"]",
                               "denoise.two_history.gradient_beta=0.85", "output.exposure=-1.5",
                               "memory_budget=\"3GiB\"", "denoise.device=1"});
    nlohmann::json j = ConfigToJson(c);
    CHECK(j["camera"]["ipd"].get<double>() == 0.0655);  // shortest decimal, not 0.06549999...
    CHECK(j["run"]["seed"].get<int64_t>() == 4000000000ll);
    CHECK(j["memory_budget"].get<uint64_t>() == 3ull << 30);
    RunConfig back = ConfigFromJson(j);
    CHECK(ConfigToJson(back) == j);
    CHECK(back.camera.ipd == c.camera.ipd);
    CHECK(back.camera.fovDeg == c.camera.fovDeg);
    CHECK(back.gaze.amplitude == c.gaze.amplitude);
    CHECK(back.denoise.params.twoHistory.gradientBeta == c.denoise.params.twoHistory.gradientBeta);
    CHECK(back.foveation.omega0Deg == c.foveation.omega0Deg);  // 1/48 survives the decimal trip
    // Through TOML text as well.
    RunConfig fromToml = ConfigFromTomlString(ConfigToToml(c), "manifest.toml");
    CHECK(ConfigToJson(fromToml) == j);
    // JSON with an unknown key is rejected like TOML.
    j["camera"]["zoom"] = 2;
    CHECK_THROWS_WITH(ConfigFromJson(j), Catch::Contains("camera.zoom"));
}

TEST_CASE("CLI options: -c, repeated --set, --memory-budget", "[config]") {
    TempFile file("cli.toml", "[camera]\nwidth = 100\nheight = 50\n");
    CLI::App app;
    CLI::App* cmd = app.add_subcommand("run");
    ConfigOptions options;
    AddConfigOptions(cmd, options);
    std::vector<std::string> args = {"fovrt", "run", "-c", file.path.string(), "--set", "camera.width=200",
                                     "--set", "foveation.spp_inside=4", "--memory-budget", "1MiB"};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    app.parse(int(argv.size()), argv.data());
    REQUIRE(options.sets.size() == 2);
    RunConfig c = ResolveConfig(options);
    CHECK(c.camera.width == 200);
    CHECK(c.camera.height == 50);
    CHECK(c.foveation.sppInside == 4);
    CHECK(c.memoryBudget == 1ull << 20);
}

TEST_CASE("Experiment files: ignored tables, overlay tables, and the shipped presets", "[config]") {
    TempFile file("exp.toml", "[camera]\nwidth = 1280\nheight = 720\n[experiment]\nscenes = [\"cornell\"]\n"
                              "[experiment.quick.camera]\nwidth = 320\nheight = 180\n"
                              "[experiment.quick.run]\nframes = 0\n");
    // Without telling the loader, [experiment] is an unknown key.
    CHECK_THROWS_WITH(Resolve(file.path.string(), {}), Catch::Contains("experiment"));
    ConfigOptions options;
    options.configPath = file.path.string();
    options.ignoredTables = {"experiment"};
    CHECK(ResolveConfig(options).camera.width == 1280);
    // The overlay merges over the file; its bad value is reported with file:line and the table.
    options.overlayTables = {"experiment.quick"};
    CHECK_THROWS_WITH(ResolveConfig(options), Catch::Contains("'run.frames'") && Catch::Contains("exp.toml:10"));
    options.sets = {"run.frames=2"};  // --set still wins over the overlay
    RunConfig c = ResolveConfig(options);
    CHECK(c.camera.width == 320);
    CHECK(c.camera.height == 180);
    CHECK(c.run.frames == 2);

    // The experiment helper: same resolution, plus the raw [experiment] table.
    ExperimentTable experiment;
    ConfigOptions plain;
    plain.configPath = file.path.string();
    plain.sets = {"run.frames=3"};
    c = ResolveExperimentConfig(plain, true, experiment);
    CHECK(c.camera.width == 320);
    CHECK(c.run.frames == 3);
    REQUIRE(experiment.table.get("scenes"));
    CHECK(experiment.table.get("scenes")->as_array()->size() == 1);
    CHECK(experiment.table.get("quick"));
    CHECK(experiment.Origin("scenes") == file.path.string() + ":5");
    // --set experiment.KEY lands in the table, with its origin.
    plain.sets = {"experiment.scenes=[\"room\", \"cornell\"]"};
    ResolveExperimentConfig(plain, false, experiment);
    CHECK(experiment.table.get("scenes")->as_array()->size() == 2);
    CHECK(experiment.Origin("scenes") == "--set experiment.scenes=[\"room\", \"cornell\"]");
    CHECK(ResolveExperimentConfig(plain, false, experiment).camera.width == 1280);

    // Every shipped preset loads, with and without its quick overlay.
    int presets = 0;
    fs::path dir = fovrt::test::SourceDir() / "presets";
    if (fs::exists(dir)) {
        for (const auto& entry : fs::directory_iterator(dir)) {
            if (entry.path().extension() != ".toml") continue;
            INFO("preset " << entry.path());
            ConfigOptions preset;
            preset.configPath = entry.path().string();
            preset.ignoredTables = {"experiment"};
            CHECK_NOTHROW(ResolveConfig(preset));
            preset.overlayTables = {"experiment.quick"};
            CHECK_NOTHROW(ResolveConfig(preset));
            ++presets;
        }
    }
    if (presets == 0) WARN("no presets/*.toml found");
}

TEST_CASE("Paths written in a config file are from its folder; --set paths from the working directory",
          "[config]") {
    const fs::path dir = test::ScratchDir("fovrt-config-paths");
    fs::create_directories(dir / "cfg");
    const fs::path file = dir / "cfg" / "run.toml";
    std::ofstream(file) << "[scene]\nname = \"../scenes/lab.toml\"\n"
                           "[gaze]\nsource = \"recording\"\nrecording_path = \"../gaze/rec.csv\"\n"
                           "trace_path = \"/abs/t.csv\"\n"
                           "[denoise.rae]\nweights = \"w.raew\"\n"
                           "[output]\ndir = \"out/x\"\n"
                           "[experiment]\nscenes = [\"cornell\"]\n"
                           "[experiment.quick.denoise.rae]\nweights_spp = \"q.raew\"\n";
    auto normal = [](const fs::path& p) { return fs::absolute(p).lexically_normal().string(); };
    ConfigOptions options;
    options.configPath = file.string();
    ExperimentTable experiment;
    RunConfig c = ResolveExperimentConfig(options, true, experiment);
    CHECK(c.scene.name == normal(dir / "scenes/lab.toml"));
    CHECK(c.gaze.recordingPath == normal(dir / "gaze/rec.csv"));
    CHECK(c.gaze.tracePath == "/abs/t.csv");  // absolute: as written
    CHECK(c.denoise.params.rae.weights == normal(dir / "cfg/w.raew"));
    CHECK(c.denoise.params.rae.weightsSpp == normal(dir / "cfg/q.raew"));  // inside an overlay table
    CHECK(c.output.dir == "out/x");  // where to write: from the working directory (docs/usage.md)
    // A built-in scene name stays a name; --set paths are from the working directory.
    options.sets = {"scene.name=cornell", "gaze.recording_path=here.csv"};
    c = ResolveExperimentConfig(options, false, experiment);
    CHECK(c.scene.name == "cornell");
    CHECK(c.gaze.recordingPath == normal(fs::current_path() / "here.csv"));

    // A run manifest's config (JSON) names the same files when re-read; so does the resolved
    // config written as TOML and read from another folder, for every path it was given.
    options.sets.clear();
    c = ResolveExperimentConfig(options, false, experiment);
    CHECK(ConfigToJson(ConfigFromJson(ConfigToJson(c))) == ConfigToJson(c));
    fs::create_directories(dir / "elsewhere");
    std::ofstream(dir / "elsewhere/config.toml") << ConfigToToml(c);
    const RunConfig back = LoadConfigFile((dir / "elsewhere/config.toml").string());
    CHECK(back.scene.name == c.scene.name);
    CHECK(back.gaze.recordingPath == c.gaze.recordingPath);
    CHECK(back.denoise.params.rae.weights == c.denoise.params.rae.weights);
}

TEST_CASE("A shipped preset names its recording and weights from any working directory", "[config]") {
    const fs::path presets = test::SourceDir() / "presets";
    const fs::path elsewhere = test::ScratchDir("fovrt-config-cwd");
    const fs::path before = fs::current_path();
    fs::current_path(elsewhere);
    ConfigOptions options;
    options.ignoredTables = {"experiment"};
    options.configPath = (presets / "eye-tracker-latency.toml").string();
    const RunConfig latency = ResolveConfig(options);
    options.configPath = (presets / "rae.toml").string();
    const RunConfig rae = ResolveConfig(options);
    fs::current_path(before);
    CHECK(latency.gaze.recordingPath ==
          (test::SourceDir().parent_path() / "shared/gaze/vr-kitchen-p10.csv").lexically_normal().string());
    CHECK(fs::exists(rae.denoise.params.rae.weights));
    CHECK(fs::exists(rae.denoise.params.rae.weightsSpp));
}

TEST_CASE("The eye FOV: camera.fov_deg when given, else symmetric from the scene", "[config]") {
    RunConfig config = DefaultConfig();  // 640×360, no explicit FOV
    Scene scene;
    scene.horizontalFovDegrees = 60.0f;
    Fov fov = ResolveFov(config, scene);
    CHECK(fov.angleRight == Approx(Radians(30.0f)));
    CHECK(fov.angleLeft == Approx(Radians(-30.0f)));
    CHECK(std::tan(fov.angleUp) == Approx(std::tan(Radians(30.0f)) * 360.0f / 640.0f));
    config.camera.fovDeg = std::array<float, 4>{-50, 40, 45, -35};
    fov = ResolveFov(config, scene);
    CHECK(fov.angleLeft == Approx(Radians(-50.0f)));
    CHECK(fov.angleDown == Approx(Radians(-35.0f)));
}

TEST_CASE("Frame times: run.fps when given, else the scene's frame rate", "[config]") {
    RunConfig config = DefaultConfig();  // cornell; fps 0: the scene's frame rate
    config.camera.width = 16;
    config.camera.height = 16;
    const float sceneRate = FramePipeline(config).GetScene().frameRate;
    REQUIRE(sceneRate > 0.0f);
    CHECK(FramePipeline(config).TimeOf(15) == Approx(15.0 / sceneRate));
    config.run.fps = 90.0f;
    CHECK(FramePipeline(config).TimeOf(45) == Approx(0.5));
}

TEST_CASE("a --set value that is not UTF-8 is refused up front naming the key", "[config]") {
    ConfigOptions options;
    options.sets = {"output.dir=out-\xff\xfe"};
    CHECK_THROWS_WITH(ResolveConfig(options),
                      Catch::Equals("--set output.dir: the value is not valid UTF-8 (config values are written to JSON "
                                    "manifests)"));
    options.sets = {"output.dir=out-\xc3\xa9t\xc3\xa9"};  // valid UTF-8 ("été") is kept as given
    CHECK(ResolveConfig(options).output.dir == "out-\xc3\xa9t\xc3\xa9");
}

namespace {

// A number inside `range` other than `value`: half-way to the nearer bound (the far one from a
// bound), one step for integers, 1.5 further where that side is unbounded.
template <class T>
T OtherNumber(const ParamRange& range, T value) {
    double target = double(value) - range.min < range.max - double(value) ? range.min : range.max;
    if (double(value) == range.min) target = range.max;
    if (double(value) == range.max) target = range.min;
    if (std::isinf(target)) return T(double(value) + (target > 0 ? 1.5 : -1.5));
    if constexpr (std::is_integral_v<T>) return T(double(value) + (target > double(value) ? 1.0 : -1.0));
    return T((double(value) + target) / 2.0);
}

// A valid value for the key other than `value`.
template <class T>
T OtherValue(const ParamInfo& info, const T& value, const RunConfig& base) {
    const std::string key = info.key;
    if constexpr (std::is_same_v<T, bool>) {
        return !value;
    } else if constexpr (std::is_same_v<T, std::string>) {
        if (info.names != nullptr)
            for (const char* name : info.names())
                if (value != name) return name;
        return key == "denoise.device" ? std::string("cpu") : value + "x";
    } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
        T more = value;
        more.push_back("asvgf");
        return more;
    } else if constexpr (std::is_same_v<T, vec2>) {
        return vec2(OtherNumber(info.range, value.x), OtherNumber(info.range, value.y));
    } else if constexpr (std::is_same_v<T, FovDegrees>) {
        return std::array<float, 4>{-40.0f, 35.5f, 30.0f, -25.25f};
    } else {
        if (key == "foveation.ray_budget") return T(2 * base.camera.width * base.camera.height);
        return OtherNumber(info.range, value);
    }
}

// Defaults with the keys other keys depend on set: a trace and a recording to play, a tracker
// rate for blinks and predictions, degree-sized amplitudes for units = "deg".
RunConfig RoundTripBase() {
    // The perceptual model: foveation.content_masking and a pooling other than energy are refused
    // with any other.
    // run.warmup_frames needs as many frames before run.first_frame.
    return Resolve("", {"gaze.trace_path=a.csv", "gaze.recording_path=b.csv", "gaze.tracker_rate_hz=120",
                        "gaze.amplitude=[20, 10]", "foveation.model=\"perceptual\"", "run.first_frame=100"});
}

// The value of `key` in `config`, as its member type.
template <class T>
T ValueOf(const RunConfig& config, const std::string& key) {
    std::optional<T> found;
    ForEachSetting(config, [&](const ParamInfo& info, const auto& member) {
        if constexpr (std::is_same_v<std::decay_t<decltype(member)>, T>)
            if (key == info.key) found = member;
    });
    REQUIRE(found);
    return *found;
}

}  // namespace

TEST_CASE("Settings tables: every key round-trips a non-default value through TOML and JSON", "[config]") {
    const RunConfig base = RoundTripBase();
    std::set<std::string> keys;
    ForEachSetting(base, [&](const ParamInfo& info, const auto& baseValue) {
        using T = std::decay_t<decltype(baseValue)>;
        INFO(info.key);
        CHECK(keys.insert(info.key).second);  // each key once
        const T changed = OtherValue(info, baseValue, base);
        REQUIRE(!(changed == baseValue));
        RunConfig c = base;
        ForEachSetting(c, [&](const ParamInfo& row, auto& member) {
            if constexpr (std::is_same_v<std::decay_t<decltype(member)>, T>)
                if (std::string(row.key) == info.key) member = changed;
        });
        const RunConfig back = ConfigFromTomlString(ConfigToToml(c), "roundtrip.toml");
        CHECK(ValueOf<T>(back, info.key) == changed);
        CHECK(ValueOf<T>(ConfigFromJson(ConfigToJson(c)), info.key) == changed);
        CHECK(ConfigToJson(back) == ConfigToJson(c));
    });
    CHECK(keys.size() == 103);
    RunConfig c = DefaultConfig();
    c.denoise.params.precision = Precision::Fp16;
    CHECK(ConfigFromTomlString(ConfigToToml(c)).denoise.params.precision == Precision::Fp16);
}

TEST_CASE("config --keys lists every key the writer writes, with its default", "[config]") {
    RunConfig all = DefaultConfig();
    all.camera.fovDeg = std::array<float, 4>{-40, 40, 30, -30};  // the one key absent by default
    std::set<std::string> written;
    std::function<void(const nlohmann::json&, const std::string&)> collect = [&](const nlohmann::json& j,
                                                                                 const std::string& prefix) {
        for (const auto& [key, value] : j.items()) {
            const std::string path = prefix.empty() ? key : prefix + "." + key;
            if (value.is_object()) collect(value, path);
            else written.insert(path);
        }
    };
    collect(ConfigToJson(all), "");
    std::set<std::string> listed;
    for (const SettingLine& line : DescribeSettings()) {
        INFO(line.key);
        CHECK(listed.insert(line.key).second);
        CHECK(!line.allowed.empty());
        CHECK(!line.doc.empty());
        if (line.key == "camera.fov_deg") CHECK(line.defaultValue.empty());
        else CHECK(!line.defaultValue.empty());
    }
    CHECK(listed == written);
    CHECK(listed.size() == 104);  // the 103 table rows and denoise.precision
}

TEST_CASE("Settings tables: a value outside its row fails in one line naming the key and the range", "[config]") {
    int checked = 0;
    const RunConfig defaults = DefaultConfig();
    ForEachSetting(defaults, [&](const ParamInfo& info, const auto& value) {
        using T = std::decay_t<decltype(value)>;
        const ParamRange& r = info.range;
        std::vector<std::string> bad;
        if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
            for (double outside : {r.minOpen ? r.min : r.min - 1.0, r.maxOpen ? r.max : r.max + 1.0})
                if (std::isfinite(outside) && std::abs(outside) < 1e15) bad.push_back(fmt::format("{}", outside));
        } else if constexpr (std::is_same_v<T, vec2>) {
            if (std::isfinite(r.min)) bad.push_back(fmt::format("[{}, 0]", r.minOpen ? r.min : r.min - 1.0));
            else bad.push_back("[nan, 0]");
        } else if constexpr (std::is_same_v<T, FovDegrees>) {
            bad.push_back("[-90, 10, 10, -10]");
        } else if constexpr (std::is_same_v<T, std::string>) {
            if (info.names != nullptr || info.nonEmpty) bad.push_back("\"\"");
        }
        for (const std::string& value : bad) {
            const std::string set = fmt::format("{}={}", info.key, value);
            INFO(set);
            ++checked;
            std::string message;
            try {
                Resolve("", {set});
            } catch (const Error& e) {
                message = e.what();
            }
            CHECK(message.find('\n') == std::string::npos);
            CHECK(message.find(fmt::format("'{}'", info.key)) != std::string::npos);
            if (info.names != nullptr) {
                for (const char* name : info.names()) CHECK(message.find(name) != std::string::npos);
            } else if (info.nonEmpty && !std::is_arithmetic_v<T>) {
                CHECK(message.find("must not be empty") != std::string::npos);
            } else {
                CHECK(message.find("out of range " + r.Describe()) != std::string::npos);
            }
        }
    });
    CHECK(checked > 100);
    // The rule between keys names both.
    CHECK_THROWS_WITH(Resolve("", {"denoise.svgf.atrous_iterations=2", "denoise.svgf.feedback_iteration=3"}),
                      Catch::Contains("'denoise.svgf.feedback_iteration'") &&
                          Catch::Contains("denoise.svgf.atrous_iterations = 2"));
}

TEST_CASE("foveation.radius_deg: one range, [0, 180), in the reader and the model's checks", "[config]") {
    // An eccentricity lies in [0°, 180°]; 180° would make every direction foveal.
    CHECK(Resolve("", {"foveation.radius_deg=179.5"}).foveation.radiusDeg == 179.5f);
    CHECK_THROWS_WITH(Resolve("", {"foveation.radius_deg=180"}),
                      Catch::Contains("'foveation.radius_deg'") && Catch::Contains("out of range [0, 180)"));
    FoveationParams params;
    params.radiusDeg = 179.5f;
    CHECK_NOTHROW(ValidateFoveationParams(params));
    params.radiusDeg = 180.0f;
    CHECK_THROWS_WITH(ValidateFoveationParams(params),
                      Catch::Equals("foveation.radius_deg: 180 is out of range [0, 180)"));
}

TEST_CASE("the modules' checks walk the same rows as the reader", "[config]") {
    // For every [foveation] and [gaze] row: a value the reader refuses, the module refuses too, naming
    // the key and the same range.
    auto outside = [](const ParamRange& r) { return std::isfinite(r.min) ? r.min - 1.0 : r.max + 1.0; };
    int checked = 0;
    auto probe = [&](const auto& defaults, const auto& table, auto validate) {
        VisitRows(defaults, table, [&](const ParamInfo& info, const auto& value) {
            using T = std::decay_t<decltype(value)>;
            if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool> && !std::is_unsigned_v<T>) {
                auto bad = defaults;
                VisitRows(bad, table, [&](const ParamInfo& row, auto& member) {
                    if constexpr (std::is_same_v<std::decay_t<decltype(member)>, T>)
                        if (std::string(row.key) == info.key) member = T(outside(info.range));
                });
                INFO(info.key);
                ++checked;
                CHECK_THROWS_WITH(validate(bad), Catch::StartsWith(std::string(info.key) + ": ") &&
                                                     Catch::Contains("out of range " + info.range.Describe()));
            }
        });
    };
    probe(FoveationParams{}, FoveationParamTable(), [](const FoveationParams& p) { ValidateFoveationParams(p); });
    probe(GazeParams{}, GazeParamTable(), [](const GazeParams& p) { ValidateGazeParams(p); });
    probe(TrackerParams{}, TrackerParamTable(), [](const TrackerParams& p) { ValidateTrackerParams(p); });
    CHECK(checked >= 25);
}

TEST_CASE("a slider span outside its row's range is a malformed row", "[config]") {
    CHECK(ParamRowProblem({.key = "k", .range = Closed(0, 10), .doc = "d", .slider = Closed(1, 9)}) == nullptr);
    CHECK(ParamRowProblem({.key = "k", .range = Closed(0, 10), .doc = "d", .slider = Closed(1, 11)}) != nullptr);
    CHECK(ParamRowProblem({.key = "k", .range = OpenMin(0, 10), .doc = "d", .slider = Closed(0, 5)}) != nullptr);
    // Every row the preview panel slides has a span (the panel reads it by key).
    for (const char* key : {"foveation.spp_inside", "foveation.radius_px", "foveation.foveal_deg",
                            "foveation.peripheral_deg", "foveation.mar_slope", "foveation.uniform_spp",
                            "foveation.spp_outside", "foveation.spp_min", "foveation.spp_floor",
                            "foveation.noise_frequency", "foveation.spp_cap", "foveation.spp_cap_ratio"})
        CHECK(!FindRow(FoveationParamTable(), key)->slider.Empty());
}

// Every denoiser takes a foveation that may put 0 in the spp map: the RAE fills such pixels from
// their sampled neighbours (RaeFillEmptyPixels), the SVGF family keeps their histories.
TEST_CASE("every denoiser, the RAE included, is accepted with a foveation below 1 spp", "[config]") {
    CHECK_NOTHROW(ConfigFromTomlString("[denoise]\ndenoisers = [\"svgf\", \"rae\"]\n[foveation]\nspp_outside = 0.25\n"));
    CHECK_NOTHROW(
        ConfigFromTomlString("[denoise]\ndenoisers = [\"rae-spp\"]\n[foveation]\nmodel = \"uniform\"\nuniform_spp = 0.5\n"));
    CHECK_NOTHROW(ConfigFromTomlString("[camera]\nwidth = 64\nheight = 32\n[denoise]\ndenoisers = [\"rae\"]\n"
                                       "[foveation]\nspp_floor = 0.0625\nray_budget = 1024\n"));
}
