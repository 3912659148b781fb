// RunConfig: defaults, TOML load, --set overrides, unknown keys, bad values, JSON/TOML round trip.
#include <filesystem>
#include <fstream>
#include <type_traits>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "config/config.h"
#include "config/config_cli.h"
#include "config/config_io.h"
#include "core/error.h"
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
    CHECK(c.denoise.params.precision == Precision::Fp32);
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
    // A known variant with a suffix its family refuses is refused here, before any rendering.
    CHECK_THROWS_WITH(Resolve("", {"denoise.denoisers=[\"rae+brdf\"]"}),
                      Catch::Contains("denoise.denoisers") && Catch::Contains("albedo-demodulated"));
    CHECK(Resolve("", {"denoise.denoisers=[\"rae+albedo\", \"svgf+brdf\"]"}).denoise.denoisers.size() == 2);
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
    fails({"foveation.spp_inside=17"}, "foveation.spp_inside");
    fails({"foveation.model=gaussian"}, "foveation.model");
    fails({"foveation.peripheral_deg=1"}, "foveation.peripheral_deg");
    fails({"foveation.ray_budget=10"}, "foveation.ray_budget");
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

TEST_CASE("Eye FOV and frame times", "[config]") {
    CameraConfig camera;  // 640×360, no explicit FOV
    Fov fov = EyeFov(camera, 60.0f);
    CHECK(fov.angleRight == Approx(Radians(30.0f)));
    CHECK(fov.angleLeft == Approx(Radians(-30.0f)));
    CHECK(std::tan(fov.angleUp) == Approx(std::tan(Radians(30.0f)) * 360.0f / 640.0f));
    camera.fovDeg = std::array<float, 4>{-50, 40, 45, -35};
    fov = EyeFov(camera, 60.0f);
    CHECK(fov.angleLeft == Approx(Radians(-50.0f)));
    CHECK(fov.angleDown == Approx(Radians(-35.0f)));
    RunSettings run;  // fps 0: the scene's frame rate
    CHECK(FrameTimeSeconds(run, 30.0f, 15) == Approx(0.5));
    run.fps = 90.0f;
    CHECK(FrameTimeSeconds(run, 30.0f, 45) == Approx(0.5));
}

namespace {

// An in-range value other than `value`: the other boolean, or a step towards the far bound.
template <class T>
T NonDefault(const ParamInfo& info, T value) {
    if constexpr (std::is_same_v<T, bool>) {
        return !value;
    } else {
        const double far = value - info.range.min < info.range.max - value ? info.range.max : info.range.min;
        T next = std::is_same_v<T, int> ? T(value + (far > value ? 1 : -1)) : T((double(value) + far) / 2.0);
        return next;
    }
}

}  // namespace

TEST_CASE("Denoiser parameter tables: every key round-trips through the TOML writer and reader", "[config]") {
    int keys = 0;
    const DenoiserParams defaults;
    ForEachDenoiserParam(defaults, [&](const ParamInfo& info, const auto& defaultValue) {
        INFO(info.key);
        ++keys;
        RunConfig c = DefaultConfig();
        auto changed = NonDefault(info, defaultValue);
        REQUIRE(changed != defaultValue);
        ForEachDenoiserParam(c.denoise.params, [&](const ParamInfo& row, auto& member) {
            if constexpr (std::is_same_v<std::decay_t<decltype(member)>, decltype(changed)>)
                if (row.key == info.key) member = changed;
        });
        const RunConfig back = ConfigFromTomlString(ConfigToToml(c), "roundtrip.toml");
        ForEachDenoiserParam(back.denoise.params, [&](const ParamInfo& row, const auto& member) {
            if constexpr (std::is_same_v<std::decay_t<decltype(member)>, decltype(changed)>)
                if (row.key == info.key) CHECK(member == changed);
        });
        CHECK(ConfigToJson(back) == ConfigToJson(c));
    });
    CHECK(keys == 18);  // 10 svgf + 4 asvgf (2 of them anti-lag) + 2 two-history + 2 two-history-stable
    RunConfig c = DefaultConfig();
    c.denoise.params.precision = Precision::Fp16;
    CHECK(ConfigFromTomlString(ConfigToToml(c)).denoise.params.precision == Precision::Fp16);
}

TEST_CASE("Denoiser parameter tables: each numeric key out of range fails naming it", "[config]") {
    const DenoiserParams defaults;
    int numeric = 0;
    ForEachDenoiserParam(defaults, [&](const ParamInfo& info, const auto& value) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(value)>, bool>) {
            ++numeric;
            const ParamRange& r = info.range;
            for (double outside : {r.minOpen ? r.min : r.min - 1.0, r.maxOpen ? r.max : r.max + 1.0}) {
                const std::string set = fmt::format("{}={}", info.key, outside);
                INFO(set);
                CHECK_THROWS_WITH(Resolve("", {set}),
                                  Catch::Contains(fmt::format("'{}'", info.key)) && Catch::Contains("out of range"));
            }
        }
    });
    CHECK(numeric == 14);
    // The rule between keys names both.
    CHECK_THROWS_WITH(Resolve("", {"denoise.svgf.atrous_iterations=2", "denoise.svgf.feedback_iteration=3"}),
                      Catch::Contains("'denoise.svgf.feedback_iteration'") &&
                          Catch::Contains("denoise.svgf.atrous_iterations = 2"));
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
