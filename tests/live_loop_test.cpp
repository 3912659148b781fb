// LiveLoop (src/live/live_loop.h) without a window: frames come out in order on the render
// thread (and, pipelined, on two threads, equal to the serial loop's), pause holds and step renders exactly one frame, a denoiser switch starts from empty
// histories (the first frame after it equals a fresh denoiser's), the "vdp" view carries the
// metric's temporal channels across frames and restarts them on a denoiser switch, and a failure
// on the render thread is reported instead of lost.
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include "config/config.h"
#include "denoise/denoiser_factory.h"
#include "live/live_loop.h"
#include "pipeline/frame_pipeline.h"
#include "pipeline/reference_cache.h"

using namespace fovrt;

namespace {

RunConfig SmallConfig() {
    RunConfig config = DefaultConfig();
    config.scene.name = "cornell";
    config.camera.width = 32;
    config.camera.height = 18;
    config.gaze.source = "static";
    config.denoise.device = "cpu";
    config.denoise.denoisers = {"svgf"};
    return config;
}

// The scene's camera path and the static gaze, as a headless run would take them.
class PathSource : public FrameSource {
public:
    explicit PathSource(const RunConfig& config) : pipeline_(config) {}
    SourcedFrame Next(uint32_t frame, double) override {
        if (failAt_ && frame == *failAt_) throw std::runtime_error("gaze tracker unplugged");
        SourcedFrame f;
        f.request = pipeline_.RequestAt(frame);
        f.gazeTakenAt = LiveClock::now();
        return f;
    }
    std::optional<uint32_t> failAt_;

private:
    FramePipeline pipeline_;
};

template <typename F>
void WaitFor(F done) {  // a bound on a hang, not a timing assertion
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!done() && std::chrono::steady_clock::now() < give_up)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    REQUIRE(done());
}

}  // namespace

TEST_CASE("live loop publishes every frame in order and stops after maxFrames", "[live]") {
    const RunConfig config = SmallConfig();
    PathSource source(config);
    LiveLoop loop(config, nullptr, source);
    std::vector<uint64_t> seen;
    loop.OnFrameDone([&](const LiveFrame& f) { seen.push_back(f.number); });
    loop.Start(4);
    WaitFor([&] { return loop.Finished(); });
    CHECK_FALSE(loop.Error());
    CHECK(seen == std::vector<uint64_t>{1, 2, 3, 4});
    const auto latest = loop.Latest();
    REQUIRE(latest);
    CHECK(latest->number == 4);
    CHECK(latest->stereo.frame == 3);
    CHECK(latest->shown[0].rgb.width() == 32);
    CHECK(latest->timings.rays > 0);
}

// Pipelined, frame N+1 is traced on one thread while frame N is denoised on another (the
// preview's --pipelined): the hand-over must neither drop, repeat nor mix frames, so every frame
// equals the serial loop's. Under TSan (scripts/sanitize.sh) this is the test where the loop's two
// render threads meet.
TEST_CASE("live loop: pipelined frames equal the serial loop's, in order", "[live]") {
    const RunConfig config = SmallConfig();
    auto run = [&](bool pipelined) {
        PathSource source(config);
        LiveLoop loop(config, nullptr, source);
        std::vector<std::pair<uint64_t, Plane<vec3>>> frames;
        loop.OnFrameDone([&](const LiveFrame& f) { frames.emplace_back(f.number, f.denoised[1]); });
        loop.Start(5, pipelined);
        WaitFor([&] { return loop.Finished(); });
        CHECK_FALSE(loop.Error());
        return frames;
    };
    const auto serial = run(false);
    const auto pipelined = run(true);
    REQUIRE(serial.size() == 5);
    REQUIRE(pipelined.size() == 5);
    for (size_t i = 0; i < serial.size(); ++i) {
        CHECK(pipelined[i].first == i + 1);
        CHECK(pipelined[i].second.vector() == serial[i].second.vector());
    }
}

TEST_CASE("live loop: pause holds, step renders exactly one frame", "[live]") {
    const RunConfig config = SmallConfig();
    PathSource source(config);
    LiveLoop loop(config, nullptr, source);
    loop.SetPaused(true);
    loop.Start();
    loop.Step();
    WaitFor([&] { return loop.FramesRendered() == 1; });
    loop.Step();
    loop.Step();
    WaitFor([&] { return loop.FramesRendered() == 3; });
    loop.Stop();
    CHECK(loop.FramesRendered() == 3);
}

TEST_CASE("live loop: a denoiser switch starts from empty histories", "[live]") {
    const RunConfig config = SmallConfig();
    PathSource source(config);
    LiveLoop loop(config, nullptr, source);
    loop.SetPaused(true);
    loop.Start();
    for (int i = 0; i < 3; ++i) loop.Step();
    WaitFor([&] { return loop.FramesRendered() == 3; });
    loop.SetDenoiser("two-history");
    loop.Step();
    WaitFor([&] { return loop.FramesRendered() == 4; });
    const auto frame = loop.Latest();
    REQUIRE(frame->denoiser == "two-history");
    for (int eye = 0; eye < 2; ++eye) {
        const FrameInputs& inputs = frame->stereo.eyes[size_t(eye)].inputs;
        CHECK(inputs.cameraCut);  // motion vectors restart with the new histories
        auto fresh = CreateDenoiser("two-history", "cpu", ParamsForDenoiser("two-history", config.denoise.params));
        Plane<vec3> expected;
        fresh->Denoise(inputs, expected);
        CHECK(expected.vector() == frame->denoised[size_t(eye)].vector());
    }
    const auto views = loop.ViewNames();
    CHECK(std::find(views.begin(), views.end(), "spp") != views.end());
}

TEST_CASE("live loop: the vdp view keeps the metric across frames and restarts it on a switch", "[live][vdp]") {
    RunConfig config = SmallConfig();
    config.camera.width = 48;
    config.camera.height = 32;
    config.reference.spp = 4;
    config.reference.cacheDir = (std::filesystem::temp_directory_path() / "fovrt_live_loop_vdp").string();
    std::filesystem::remove_all(config.reference.cacheDir);
    {  // the references of the first frames, as `fovrt reference` leaves them
        FramePipeline pipeline(config);
        ReferenceCache cache(config.reference.cacheDir);
        const uint64_t fingerprint = SceneFingerprint(pipeline.GetScene());
        for (uint32_t frame = 0; frame < 4; ++frame) {
            pipeline.SetFrame(frame);
            for (int eye = 0; eye < 2; ++eye)
                cache.GetOrRender(MakeReferenceKey(pipeline.GetScene(), fingerprint, frame, pipeline.TimeOf(frame), eye,
                                                   pipeline.RigAt(frame).Eye(eye), config.reference.spp,
                                                   config.run.maxDepth, config.reference.seed),
                                  pipeline.GetRenderer());
        }
    }
    PathSource source(config);
    LiveLoop loop(config, nullptr, source);
    loop.SetView("vdp");
    loop.SetPaused(true);
    loop.Start();
    std::vector<std::shared_ptr<const LiveFrame>> frames;
    auto step = [&](uint64_t n) {
        loop.Step();
        WaitFor([&] { return loop.FramesRendered() == n; });
        frames.push_back(loop.Latest());
    };
    step(1);
    step(2);
    loop.SetDenoiser("two-history");
    step(3);
    // The view a fresh stream gives: the frame as the first of a sequence.
    ReferenceCache cache(config.reference.cacheDir);
    const FramePipeline& pipeline = loop.Pipeline();
    auto freshView = [&](const LiveFrame& f, int eye) {
        const EyeFrame& e = f.stereo.eyes[size_t(eye)];
        const auto reference = cache.Find(MakeReferenceKey(
            pipeline.GetScene(), SceneFingerprint(pipeline.GetScene()), f.stereo.frame, f.stereo.timeSeconds, eye,
            e.camera, config.reference.spp, config.run.maxDepth, config.reference.seed));
        REQUIRE(reference);
        VdpViewStream stream(config, e.camera, pipeline.FramesPerSecond());
        ViewSources sources{&e.inputs, &e.sppMap, &f.denoised[size_t(eye)], &*reference, nullptr, &stream,
                            e.trueGazePixel};
        ViewImage view;
        REQUIRE(BuildView("vdp", sources, view));
        return view.rgb.vector();
    };
    for (const auto& f : frames) {
        REQUIRE(f->view == "vdp");
        CHECK(f->shown[0].legend.find("FovVideoVDP") != std::string::npos);  // not the fallback
    }
    for (int eye = 0; eye < 2; ++eye) {
        CHECK(frames[0]->shown[size_t(eye)].rgb.vector() == freshView(*frames[0], eye));
        CHECK(frames[1]->shown[size_t(eye)].rgb.vector() != freshView(*frames[1], eye));  // frame 1 in its past
        CHECK(frames[2]->shown[size_t(eye)].rgb.vector() == freshView(*frames[2], eye));  // restarted
    }
    std::filesystem::remove_all(config.reference.cacheDir);
}

TEST_CASE("live loop: a render-thread failure is reported", "[live]") {
    const RunConfig config = SmallConfig();
    PathSource source(config);
    source.failAt_ = 2;
    LiveLoop loop(config, nullptr, source);
    loop.Start();
    WaitFor([&] { return loop.Finished(); });
    REQUIRE(loop.Error());
    CHECK(loop.Error()->find("gaze tracker unplugged") != std::string::npos);
    CHECK(loop.FramesRendered() == 2);
}
