// Replays (app/replay.h): frames rendered from free cameras and gaze, recorded, read back and
// rendered again in a fresh pipeline give bit-identical spp maps and noisy FrameInputs; the
// replay config keeps what the recording supplies and refuses what would change the frames.
#include <unistd.h>

#include <cstring>

#include "app/replay.h"
#include "app_test_configs.h"
#include "config/config.h"
#include "config/config_cli.h"
#include "config/config_io.h"
#include "core/error.h"
#include "core/rng.h"
#include "pipeline/frame_pipeline.h"
#include "session/session_record.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;

namespace {

fs::path TempDir() { return test::ScratchDir("fovrt-replay-test"); }

RunConfig SmallCornell() {
    RunConfig config = test::SmallCornellConfig();
    config.denoise.denoisers = {"asvgf"};  // the renderer also makes A-SVGF gradient samples
    return config;
}

float Jitter(Pcg32& rng, float scale) { return scale * (2.0f * rng.NextFloat() - 1.0f); }

// The headless request for `frame` moved off the scene's path: each eye turned and shifted on
// its own, asymmetric FOVs, the gaze pushed elsewhere (what a live session could send).
RecordedFrame Perturbed(const FramePipeline& pipeline, uint32_t frame, Pcg32& rng) {
    RecordedFrame out;
    out.request = pipeline.RequestAt(frame);
    out.head = pipeline.RigAt(frame).head;
    for (EyeCamera& eye : out.request.eyes) {
        Pose pose = eye.pose();
        const quat turn = glm::angleAxis(Jitter(rng, 0.1f), glm::normalize(vec3(Jitter(rng, 1), 1.0f, Jitter(rng, 1))));
        pose.orientation = glm::normalize(turn * pose.orientation);
        pose.position += vec3(Jitter(rng, 0.05f), Jitter(rng, 0.05f), Jitter(rng, 0.05f));
        Fov fov = eye.fov();
        fov.angleLeft -= 0.1f * rng.NextFloat();
        fov.angleUp += 0.05f * rng.NextFloat();
        eye = EyeCamera(pose, fov, eye.width(), eye.height());
    }
    const vec3 gaze = glm::normalize(out.request.gaze.direction + vec3(Jitter(rng, 0.2f), Jitter(rng, 0.2f), 0.0f));
    for (int i = 0; i < 3; ++i)
        out.gazeSamples.push_back({out.request.timeSeconds - 0.004 * (2 - i), gaze, true});
    out.request.gaze = out.gazeSamples.back();
    return out;
}

// The replay path of `fovrt run --replay`: the recording at `path` with its recorded config, a
// fresh pipeline whose gaze source is never asked, the frames read back and rendered one at a
// time, each handed to `check(n, request, frame)`. Returns how many frames it replayed.
template <class Check>
size_t ReplayEach(const fs::path& path, Check&& check) {
    Replay replay = OpenReplay(path, false);
    FramePipeline pipeline(ReplayPipelineConfig(replay.recorded));
    CheckReplayScene(replay, pipeline);
    FrameSequence sequence(pipeline, replay);
    RecordedFrame request;
    StereoFrame frame;
    size_t n = 0;
    while (sequence.Next(request)) {
        pipeline.Render(request.request, frame);
        check(n, request, frame);
        ++n;
    }
    return n;
}

std::vector<PlaneBytes> Planes(const FrameInputs& inputs) {
    std::vector<PlaneBytes> planes;
    inputs.ForEachPlane([&](const PlaneBytes& p) { planes.push_back(p); });
    return planes;
}

// Bitwise: the spp map, every FrameInputs plane, the gradient samples and the frame's metadata.
void RequireIdentical(const EyeFrame& a, const EyeFrame& b) {
    REQUIRE(a.sppMap.size() == b.sppMap.size());
    CHECK(std::memcmp(a.sppMap.data(), b.sppMap.data(), a.sppMap.bytes()) == 0);
    const FrameInputs& x = a.inputs;
    const FrameInputs& y = b.inputs;
    CHECK(x.frameIndex == y.frameIndex);
    CHECK(x.cameraCut == y.cameraCut);
    CHECK(std::memcmp(&x.timeSeconds, &y.timeSeconds, sizeof(double)) == 0);
    const std::vector<PlaneBytes> px = Planes(x), py = Planes(y);
    REQUIRE(px.size() == py.size());
    for (size_t i = 0; i < px.size(); ++i) {
        INFO("plane " << px[i].name);
        REQUIRE(px[i].bytes == py[i].bytes);
        if (px[i].bytes > 0) CHECK(std::memcmp(px[i].data, py[i].data, px[i].bytes) == 0);
    }
    REQUIRE(x.gradientSamples.size() == y.gradientSamples.size());
    // An empty vector's data() may be null, which memcmp must not be given even for 0 bytes.
    if (!x.gradientSamples.empty())
        CHECK(std::memcmp(x.gradientSamples.data(), y.gradientSamples.data(),
                          x.gradientSamples.size() * sizeof(GradientSample)) == 0);
}

}  // namespace

TEST_CASE("a replayed recording renders bit-identical spp maps and noisy inputs", "[app][live]") {
    const RunConfig config = SmallCornell();
    const fs::path path = TempDir() / "session.jsonl";
    const uint32_t frames[] = {0, 1, 2, 5, 6};  // the jump to 5 is a camera cut

    std::vector<StereoFrame> rendered;
    {
        FramePipeline pipeline(config);
        SessionRecorder recorder(path, ConfigToJson(config), SessionHeaderExtra(pipeline));
        Pcg32 rng(99);
        for (uint32_t frame : frames) {
            const RecordedFrame request = Perturbed(pipeline, frame, rng);
            rendered.emplace_back();
            pipeline.Render(request.request, rendered.back());
            recorder.Append(request);
        }
    }
    {
        FramePipeline headless(config);  // the recorded cameras are not the scene path's
        CHECK(headless.RequestAt(0).eyes[0].View() != rendered[0].eyes[0].camera.View());
    }
    REQUIRE(rendered[1].eyes[0].inputs.gradientSamples.size() > 0);
    REQUIRE(rendered[3].eyes[0].inputs.cameraCut);

    CHECK(OpenReplay(path, false).summary.frames == std::size(frames));
    const size_t replayed = ReplayEach(path, [&](size_t n, const RecordedFrame&, const StereoFrame& frame) {
        REQUIRE(n < rendered.size());
        for (int eye = 0; eye < 2; ++eye) {
            INFO("frame " << frames[n] << " eye " << eye);
            RequireIdentical(rendered[n].eyes[size_t(eye)], frame.eyes[size_t(eye)]);
        }
    });
    CHECK(replayed == std::size(frames));
}

TEST_CASE("a recording with a tracker model replays with its tracked gaze for the spp maps and its true gaze for the metrics",
          "[app][live]") {
    const RunConfig config = test::SmallCornellConfig();
    const fs::path path = TempDir() / "tracked.jsonl";
    // A lagging tracker: the spp maps followed a gaze 24° left of where the eye was (the disc: 8 px).
    const vec3 eye = GazeDirectionFromAngles(9.0f, 1.0f), tracker = GazeDirectionFromAngles(-15.0f, 1.0f);
    std::vector<StereoFrame> live;
    {
        FramePipeline pipeline(config);
        SessionRecorder recorder(path, ConfigToJson(config), SessionHeaderExtra(pipeline));
        for (uint32_t f = 0; f < 3; ++f) {
            RecordedFrame frame;
            frame.request = pipeline.RequestAt(f);
            frame.head = pipeline.RigAt(f).head;
            frame.request.trueGaze = GazeSample{frame.request.timeSeconds, eye, true};
            frame.request.gaze = GazeSample{frame.request.timeSeconds, tracker, true};
            frame.gazeSamples = {*frame.request.trueGaze};
            live.emplace_back();
            pipeline.Render(frame.request, live.back());
            recorder.Append(frame);
        }
    }
    const size_t replayed = ReplayEach(path, [&](size_t n, const RecordedFrame& request, const StereoFrame& frame) {
        REQUIRE(n < live.size());
        INFO("frame " << n);
        REQUIRE(request.request.trueGaze);
        CHECK(std::memcmp(&frame.gaze.direction, &tracker, sizeof(vec3)) == 0);
        CHECK(std::memcmp(&frame.trueGaze.direction, &eye, sizeof(vec3)) == 0);
        for (int e = 0; e < 2; ++e) {
            const EyeFrame& x = frame.eyes[size_t(e)];
            RequireIdentical(live[n].eyes[size_t(e)], x);
            // The spp map is centred on the tracked gaze; the metrics' centre is the true gaze.
            CHECK(x.trueGazePixel.x - x.gazePixel.x > 10.0f);
            const ivec2 at(x.gazePixel), truth(x.trueGazePixel);
            REQUIRE((truth.x >= 0 && truth.x < x.sppMap.width() && at.x >= 0 && at.x < x.sppMap.width()));
            CHECK(x.sppMap(at.x, at.y) > x.sppMap(truth.x, truth.y));
            CHECK(x.trueGazeEye == GazeInEye(x.camera, eye));
        }
    });
    CHECK(replayed == 3);
}

TEST_CASE("a replay's config keeps what the recording supplies and refuses what changes the frames", "[app][live]") {
    const RunConfig config = SmallCornell();
    const fs::path path = TempDir() / "config.jsonl";
    {
        FramePipeline pipeline(config);
        SessionRecorder recorder(path, ConfigToJson(config));
        for (uint32_t f = 3; f < 6; ++f) {
            RecordedFrame request;
            request.request = pipeline.RequestAt(f);
            request.head = pipeline.RigAt(f).head;
            recorder.Append(request);
        }
    }
    auto resolve = [&](std::vector<std::string> sets, bool allowChanges, Replay* out = nullptr) {
        Replay replay = OpenReplay(path, allowChanges);
        ConfigOptions options;
        options.sets = std::move(sets);
        RunConfig resolved = ResolveReplayConfig(replay, options, ResolveConfig, "test");
        if (out) *out = replay;
        return resolved;
    };

    Replay replay;
    RunConfig resolved = resolve({"output.dir=elsewhere", "denoise.svgf.alpha_color=0.5"}, false, &replay);
    CHECK(resolved.output.dir == "elsewhere");
    CHECK(resolved.denoise.params.svgf.alphaColor == 0.5f);
    CHECK(resolved.run.frames == 3);
    CHECK(resolved.run.firstFrame == 3);
    CHECK(replay.ignored.empty());
    CHECK(replay.changed.empty());

    // Supplied by the recording: the config's value is ignored (and listed).
    resolved = resolve({"gaze.source=static", "run.frames=40"}, false, &replay);
    CHECK(resolved.gaze.source == config.gaze.source);
    CHECK(resolved.run.frames == 3);
    CHECK(replay.ignored == std::vector<std::string>{"gaze.source", "run.frames"});

    // Would change the frames: refused naming the key, or rendered with --allow-changes.
    CHECK_THROWS_WITH(resolve({"foveation.model=uniform"}, false),
                      Catch::Contains(path.string() + ": replay: foveation.model = \"uniform\" differs from the recording's \"disc\""));
    CHECK_THROWS_WITH(resolve({"run.seed=7", "camera.height=20"}, false),
                      Catch::Contains("camera.height = 20 differs from the recording's 18") &&
                          Catch::Contains("run.seed = 7 differs from the recording's 1"));
    CHECK_THROWS_WITH(resolve({"denoise.denoisers=[\"svgf\"]"}, false), Catch::Contains("denoise.denoisers"));
    resolved = resolve({"foveation.model=uniform", "camera.width=64"}, true, &replay);
    CHECK(resolved.foveation.model == "uniform");
    REQUIRE(replay.changed.size() == 2);
    CHECK(replay.changed[0]["key"] == "camera.width");
    CHECK(replay.changed[1]["key"] == "foveation.model");
    // ... and the recorded eyes are rendered at the new size, same pose and FOV.
    FramePipeline pipeline(ReplayPipelineConfig(resolved));
    FrameSequence sequence(pipeline, replay);
    RecordedFrame request;
    REQUIRE(sequence.Next(request));
    CHECK(request.request.eyes[0].width() == 64);
    CHECK(request.request.eyes[0].height() == config.camera.height);

    // The scene is never another one.
    CHECK_THROWS_WITH(resolve({"scene.name=room"}, true), Catch::Contains("scene.name"));
}
