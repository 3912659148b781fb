// A trace or recording that ends: gaze.trace_start_ms must lie within the file, and a headless run
// longer than the file from there is refused (gaze.trace_end = "refuse", the default) before any
// frame is rendered, holds the last row with the frames marked ("hold"), or loops ("loop").
#include <fstream>

#include "app/experiment.h"
#include "app/replay.h"
#include "app_test_configs.h"
#include "config/config.h"
#include "core/error.h"
#include "gaze/sources.h"
#include "pipeline/frame_pipeline.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;

namespace {

// 100 ms of trace: at 30 fps frames 0..3 (0, 33.3, 66.7, 100 ms) have gaze of their own.
RunConfig ShortTraceRun(const fs::path& dir, const std::string& end) {
    const fs::path trace = dir / "short.csv";
    std::ofstream(trace) << "n,x,y\n0,0,0\n50,5,0\n100,10,0\n";
    RunConfig config = test::SmallCornellConfig();
    config.gaze.source = "trace";
    config.gaze.tracePath = trace.string();
    config.gaze.traceEnd = end;
    config.run.fps = 30.0f;
    config.run.frames = 10;
    return config;
}

}  // namespace

TEST_CASE("gaze.trace_end = refuse: a run longer than its trace is one line naming frames and keys", "[app][gaze]") {
    const fs::path dir = test::ScratchDir("fovrt-trace-end-test");
    FramePipeline pipeline(ShortTraceRun(dir, "refuse"));
    CHECK(pipeline.GazeFrames() == 4);
    CHECK_NOTHROW(pipeline.CheckGazeCovers(0, 4));
    CHECK_NOTHROW(pipeline.CheckGazeCovers(2, 2));
    try {
        pipeline.CheckGazeCovers(0, 10);
        FAIL("a 10-frame run over 4 frames of trace passed");
    } catch (const Error& e) {
        const std::string message = e.what();
        CHECK(message.find('\n') == std::string::npos);
        CHECK_THAT(message, Catch::Contains("gaze.trace_end = \"refuse\"") && Catch::Contains("need 10 frames") &&
                                Catch::Contains("short.csv") && Catch::Contains("has 4") &&
                                Catch::Contains("run.frames") && Catch::Contains("\"loop\""));
    }
    // `run` and `experiment` take their frames from a FrameSequence: refused there, before rendering.
    CHECK_THROWS_WITH(FrameSequence(pipeline), Catch::Contains("need 10 frames"));
}

TEST_CASE("gaze.trace_end = hold marks the frames past the end; loop plays from the first row again",
          "[app][gaze]") {
    const fs::path dir = test::ScratchDir("fovrt-trace-end-test");
    FramePipeline hold(ShortTraceRun(dir, "hold"));
    CHECK_NOTHROW(hold.CheckGazeCovers(0, 10));  // a warning on stderr
    CHECK(!hold.GazeHeld(3));
    CHECK(hold.GazeHeld(4));
    CHECK(GazeAnglesFromDirection(hold.RequestAt(9).gaze.direction).x == Approx(10.0f).margin(1e-4));

    FramePipeline loop(ShortTraceRun(dir, "loop"));
    CHECK_NOTHROW(loop.CheckGazeCovers(0, 10));
    CHECK(!loop.GazeHeld(9));
    // Frame 4 is at 133.3 ms: 33.3 ms into the second pass, yaw 33.3 / 50 * 5.
    CHECK(GazeAnglesFromDirection(loop.RequestAt(4).gaze.direction).x == Approx(10.0f / 3.0f).margin(1e-3));
}

TEST_CASE("gaze.trace_start_ms outside the trace names the key, the value and the trace's duration",
          "[app][gaze]") {
    const fs::path dir = test::ScratchDir("fovrt-trace-end-test");
    for (double start : {150.0, -10.0}) {
        RunConfig config = ShortTraceRun(dir, "loop");
        config.gaze.traceStartMs = start;
        INFO("start " << start);
        CHECK_THROWS_WITH(FramePipeline(config), Catch::Contains("gaze.trace_start_ms") &&
                                                     Catch::Contains(fmt::format("{} ms", start)) &&
                                                     Catch::Contains("short.csv") &&
                                                     Catch::Contains("lasts 100 ms"));
    }
    RunConfig config = ShortTraceRun(dir, "refuse");
    config.gaze.traceStartMs = 50.0;
    FramePipeline late(config);
    CHECK(late.GazeFrames() == 2);  // 50 ms left: frames 0 and 1
}

TEST_CASE("gaze.trace_end = hold: the experiment's gaze CSV marks the held frames", "[app][gaze]") {
    const fs::path dir = test::ScratchDir("fovrt-trace-end-test") / "experiment";
    fs::create_directories(dir);
    std::ofstream(dir / "short.csv") << "n,x,y\n0,0,0\n50,5,0\n100,10,0\n";
    ConfigOptions options = test::SmallExperimentOptions(dir, {.frames = 6, .experimentLines = ""});
    options.sets = {"gaze.source=trace", "gaze.trace_path=" + (dir / "short.csv").string(), "gaze.trace_end=hold",
                    "run.fps=30", "metric.vdp=false", "experiment.variants=[\"svgf\"]"};
    RunExperiment(LoadExperiment(options));
    std::ifstream csv(dir / "out" / "gaze-cornell.csv");
    std::string line;
    std::getline(csv, line);
    REQUIRE(line.substr(line.rfind(',') + 1) == "gaze_held");
    std::vector<char> held;
    while (std::getline(csv, line)) held.push_back(line.back());
    CHECK(held == std::vector<char>{'0', '0', '0', '0', '1', '1'});  // frames 4 and 5 lie past 100 ms
}
