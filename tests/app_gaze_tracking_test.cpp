// True gaze vs tracked gaze in the experiment: the spp maps follow the tracker, the metrics the
// eye. An ideal tracker (the defaults, or every tracker key set to its ideal value) gives the
// same CSV bytes; a late tracker leaves the true gaze in the unrendered (1 spp) region after a
// saccade, and the foveal error shows it. Headset recordings play their invalid rows as blinks.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/experiment.h"
#include "app_test_configs.h"
#include "pipeline/frame_pipeline.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;
using fovrt::test::ReadFile;

namespace {

// A saccade of 30° (yaw −15° -> +15°) at 100 ms: frame 3 at 30 fps is the first after it.
fs::path WriteStepTrace(const fs::path& dir) {
    const fs::path path = dir / "step.csv";
    std::ofstream(path) << "n,x,y\n0,-15,0\n99,-15,0\n100,15,0\n2000,15,0\n";
    return path;
}

ExperimentSpec SmallExperiment(const fs::path& dir, const std::string& name, const TrackerParams& tracker) {
    ExperimentSpec spec;
    spec.file = dir / (name + ".toml");
    spec.config = test::SmallCornellConfig();
    spec.config.run.frames = 10;
    spec.config.run.fps = 30.0f;
    // 96×54 with 16 spp in a 24 px disc and 1 outside, no temporal accumulation (α = 1) and one
    // à-trous iteration: the error is the noise of this frame's spp map, not history or blur.
    spec.config.camera.width = 96;
    spec.config.camera.height = 54;
    spec.config.foveation.sppInside = 16;
    spec.config.denoise.params.svgf.atrousIterations = 1;
    spec.config.denoise.params.svgf.alphaColor = 1.0f;
    spec.config.denoise.params.svgf.alphaMoments = 1.0f;
    spec.config.reference.spp = 256;
    spec.config.reference.cacheDir = (dir / "cache").string();
    spec.config.output.dir = (dir / name).string();
    spec.config.output.report = false;
    spec.config.output.writePng = false;
    spec.config.output.writeInputs = false;
    spec.config.gaze.source = "trace";
    spec.config.gaze.tracePath = WriteStepTrace(dir).string();
    spec.config.gaze.tracker = tracker;
    spec.config.denoise.denoisers = {"svgf"};
    spec.scenes = {"cornell"};
    spec.variants = {"svgf"};
    spec.baseline = "svgf";
    spec.seeds = {1};
    return spec;
}

double MeanFovealRelMse(const Results& results, int firstFrame, int lastFrame) {
    double sum = 0.0;
    int n = 0;
    for (const auto& [frame, value] : results.PerFrame("cornell", "svgf", "fovea", "relmse"))
        if (frame >= firstFrame && frame <= lastFrame) sum += value, ++n;
    return n ? sum / n : 0.0;
}

}  // namespace

TEST_CASE("an ideal tracker, default or explicit, gives identical CSV bytes", "[app][gaze][tracker]") {
    const fs::path dir = test::ScratchDir("fovrt-gaze-tracking-test");
    TrackerParams explicitIdeal;
    explicitIdeal.rateHz = 0.0;
    explicitIdeal.latencyMs = 0.0;
    explicitIdeal.noiseDeg = 0.0f;
    explicitIdeal.biasDeg = vec2(0.0f);
    explicitIdeal.dropout = 0.0;
    explicitIdeal.prediction = "none";
    explicitIdeal.seed = 99;             // no noise, no dropouts: the seed cannot matter
    explicitIdeal.saccadeDegPerS = 50.0f;  // only a predictor reads it
    RunExperiment(SmallExperiment(dir, "default", TrackerParams{}));
    RunExperiment(SmallExperiment(dir, "explicit", explicitIdeal));
    const std::string a = ReadFile(dir / "default" / "frames-cornell.csv");
    const std::string b = ReadFile(dir / "explicit" / "frames-cornell.csv");
    REQUIRE(!a.empty());
    CHECK(a == b);
    // The gaze report: the rendered fovea is on the gaze in every frame.
    const nlohmann::json summary = nlohmann::json::parse(ReadFile(dir / "default" / "summary.json"));
    const nlohmann::json& tracking = summary.at("gaze_tracking").at("cornell");
    CHECK(tracking.at("fovea_distance_deg").at("mean").get<double>() == 0.0);
    CHECK(tracking.at("outside_fovea_share").get<double>() == 0.0);
}

TEST_CASE("a late tracker misses the true gaze after a saccade; the foveal error shows the unrendered region",
          "[app][gaze][tracker]") {
    const fs::path dir = test::ScratchDir("fovrt-gaze-tracking-test");
    TrackerParams late;
    late.latencyMs = 200.0;  // frames 3..8 render the fovea where the eye was before the saccade
    const Results ontime = RunExperiment(SmallExperiment(dir, "ontime", TrackerParams{}));
    const Results delayed = RunExperiment(SmallExperiment(dir, "late", late));
    // Before the saccade both render the same frames; after it the late fovea is 30° away.
    CHECK(MeanFovealRelMse(delayed, 0, 2) == Approx(MeanFovealRelMse(ontime, 0, 2)));
    const double missed = MeanFovealRelMse(delayed, 3, 8), covered = MeanFovealRelMse(ontime, 3, 8);
    INFO("foveal relMSE frames 3-8: late " << missed << ", on time " << covered);
    CHECK(missed > 5.0 * covered);  // measured: 0.0375 vs 0.0020

    const std::string csv = ReadFile(dir / "late" / "gaze-cornell.csv");
    std::istringstream lines(csv);
    std::string line;
    std::getline(lines, line);
    CHECK(line ==
          "frame,time_s,blink,gaze_yaw_deg,gaze_pitch_deg,speed_deg_s,saccade,fovea_distance_deg,outside_fovea,gaze_held");
    for (int frame = 0; frame < 10; ++frame) {
        REQUIRE(std::getline(lines, line));
        INFO(line);
        const bool miss = frame >= 3 && frame <= 8;
        CHECK(line.substr(line.size() - 4) == (miss ? ",1,0" : ",0,0"));  // outside_fovea, gaze_held
        // Where the eye looks: the trace's yaw, −15° before the saccade at 100 ms, +15° after.
        std::istringstream fields(line);
        std::string field;
        std::vector<double> values;
        while (std::getline(fields, field, ',')) values.push_back(std::stod(field));
        REQUIRE(values.size() == 10);
        CHECK(values[3] == Approx(frame < 3 ? -15.0 : 15.0).margin(1e-4));
        CHECK(values[4] == Approx(0.0).margin(1e-4));
    }
    const nlohmann::json summary = nlohmann::json::parse(ReadFile(dir / "late" / "summary.json"));
    const nlohmann::json& tracking = summary.at("gaze_tracking").at("cornell");
    CHECK(tracking.at("outside_fovea_share").get<double>() == Approx(0.6));
    CHECK(tracking.at("saccades").get<int>() == 1);
    // The saccade frame is 3; its landing frame 4 is covered again at frame 9: 166.7 ms later.
    CHECK(tracking.at("recovery_ms").at("max").get<double>() == Approx(5000.0 / 30.0).epsilon(1e-6));
}

TEST_CASE("a headset recording's invalid rows are blink frames", "[app][gaze]") {
    const fs::path dir = test::ScratchDir("fovrt-gaze-tracking-test");
    const fs::path path = dir / "rec.csv";
    // Rows every 11 ms; 55 and 66 ms are the Vive's no-sample rows: frame 2 (66.7 ms, between the
    // rows of 66 and 77 ms) is a blink, frames 1 (between 33 and 44 ms) and 3 are not.
    std::ofstream(path) << "time,ori_x,ori_y,ori_z,dir_x,dir_y,dir_z\n"
                           "5.000,0.01,0,0,0.1,0,0.994987\n5.011,0.01,0,0,0.1,0,0.994987\n"
                           "5.022,0.01,0,0,0.1,0,0.994987\n5.033,0.01,0,0,0.1,0,0.994987\n"
                           "5.044,0.01,0,0,0.1,0,0.994987\n5.055,0,0,0,0,0,1\n5.066,0,0,0,0,0,1\n"
                           "5.077,0.01,0,0,0.1,0,0.994987\n5.200,0.01,0,0,0.1,0,0.994987\n";
    RunConfig config = test::SmallCornellConfig();
    config.run.fps = 30.0f;
    config.gaze.source = "recording";
    config.gaze.recordingPath = path.string();
    FramePipeline pipeline(config);
    for (uint32_t f = 0; f < 5; ++f) {
        INFO("frame " << f);
        const FrameRequest request = pipeline.RequestAt(f);
        CHECK(request.gaze.valid == (f != 2));
        CHECK(!request.trueGaze.has_value());  // an ideal tracker: the eye is where the gaze is
        if (f != 2) CHECK(GazeAnglesFromDirection(request.gaze.direction).x == Approx(Degrees(std::asin(0.1f))).margin(1e-3));
    }
}

TEST_CASE("the real recordings play through the pipeline with their blinks", "[app][gaze]") {
    const fs::path shared = test::SharedGaze();
    if (shared.empty()) FOVRT_SKIP("../shared/gaze is absent; real-recording test not run");
    RunConfig config = test::SmallCornellConfig();
    config.run.fps = 90.0f;
    config.gaze.source = "recording";
    config.gaze.recordingPath = (shared / "vr-kitchen-p10.csv").string();
    FramePipeline pipeline(config);
    int blinks = 0;
    for (uint32_t f = 0; f < 90 * 44; ++f) blinks += pipeline.RequestAt(f).gaze.valid ? 0 : 1;
    // The recording opens with two invalid rows 0.33 s apart (30 frames at 90 fps), and has more later.
    CHECK(blinks >= 30);
    CHECK(blinks < 90 * 44 / 10);
}
