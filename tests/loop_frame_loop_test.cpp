// The headless frame loop (loop/frame_loop.h): a restarted pipeline renders what a fresh one with
// the same seed renders (the scene and BVH are shared by an experiment's seeds), observers see
// every step in the documented order, and a pass runs only the eyes and variants it owns.
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app_test_configs.h"
#include "loop/frame_loop.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;

namespace {

// Every FrameInputs plane of both eyes of `frames` frames, as bytes.
std::vector<std::vector<float>> RenderFrames(FramePipeline& pipeline, int frames) {
    std::vector<std::vector<float>> out;
    StereoFrame frame;
    for (int f = 0; f < frames; ++f) {
        pipeline.Render(uint32_t(f), frame);
        for (const EyeFrame& e : frame.eyes) {
            std::vector<float> values;
            for (size_t p = 0; p < e.inputs.direct.size(); ++p) {
                for (int c = 0; c < 3; ++c) values.push_back(e.inputs.direct[p][c]);
                for (int c = 0; c < 3; ++c) values.push_back(e.inputs.indirect[p][c]);
                values.push_back(float(e.inputs.sampleCount[p]));
            }
            for (const GradientSample& g : e.inputs.gradientSamples) {
                values.push_back(float(g.pixel.x));
                values.push_back(float(g.pixel.y));
                values.push_back(g.newLuminance);
                values.push_back(g.oldLuminance);
            }
            out.push_back(std::move(values));
        }
    }
    return out;
}

// Records the events the loop sends, one line each.
class EventLog : public FrameLoopObserver {
public:
    void BeginSeed(size_t index, uint32_t seed, FramePipeline&) override { lines.push_back(fmt::format("seed {} {}", index, seed)); }
    void Frame(const StereoFrame& f) override { lines.push_back(fmt::format("frame {}", f.frame)); }
    void Eye(const StereoFrame&, int eye) override { lines.push_back(fmt::format("eye {}", eye)); }
    void Reference(const StereoFrame&, int eye, const ReferenceLookup& r) override {
        REQUIRE(r.image != nullptr);
        lines.push_back(fmt::format("reference {} {}", eye, r.cacheHit ? "hit" : "rendered"));
    }
    void Output(const StereoFrame&, int eye, const DenoisedOutput& o) override {
        REQUIRE(o.image != nullptr);
        REQUIRE(o.image->width() == 32);
        lines.push_back(fmt::format("output {} {}", eye, *o.name));
    }
    void EndFrame(const StereoFrame& f) override { lines.push_back(fmt::format("end {}", f.frame)); }
    void EndSeed(FramePipeline&) override { lines.push_back("end seed"); }
    std::vector<std::string> lines;
};

std::function<bool(FrameRequest&)> Frames(FramePipeline& pipeline, int count) {
    return [&pipeline, count, next = 0](FrameRequest& request) mutable {
        if (next >= count) return false;
        request = pipeline.RequestAt(uint32_t(next++));
        return true;
    };
}

}  // namespace

TEST_CASE("a restarted pipeline renders what a fresh one with that seed renders", "[loop]") {
    RunConfig config = test::SmallCornellConfig();
    // A-SVGF's gradient samples: the renderer's per-eye history must restart too.
    config.denoise.denoisers = {"asvgf"};
    config.run.seed = 7;
    FramePipeline fresh(config);
    const auto expected = RenderFrames(fresh, 3);

    config.run.seed = 3;
    FramePipeline reused(config);
    const auto other = RenderFrames(reused, 3);
    CHECK(other != expected);  // the seed matters, so the comparison below can fail
    reused.Restart(7);
    CHECK(reused.Config().run.seed == 7u);
    const auto restarted = RenderFrames(reused, 3);
    REQUIRE(restarted.size() == expected.size());
    for (size_t i = 0; i < expected.size(); ++i) CHECK(restarted[i] == expected[i]);
    CHECK(reused.GetRenderer().Stats().Rays() == fresh.GetRenderer().Stats().Rays());
}

TEST_CASE("the loop calls observers in order, once per owned eye and variant", "[loop]") {
    const fs::path dir = test::ScratchDir("fovrt_frame_loop_test");
    RunConfig config = test::SmallCornellConfig();
    config.denoise.denoisers = {"svgf", "two-history"};
    config.reference.spp = 2;
    config.reference.cacheDir = (dir / "cache").string();
    FrameLoop loop(config, true);
    EventLog log;
    loop.Attach(log);
    loop.RunSeed(0, SeedWork{config.run.seed, {}}, Frames(loop.Pipeline(), 1));
    CHECK(log.lines == std::vector<std::string>{"seed 0 1", "frame 0", "eye 0", "reference 0 rendered",
                                                "output 0 svgf", "output 0 two-history", "eye 1",
                                                "reference 1 rendered", "output 1 svgf", "output 1 two-history",
                                                "end 0", "end seed"});
    // A second pass owning only two-history on the right eye: the left eye is skipped whole; the
    // reference now comes from the cache.
    log.lines.clear();
    SeedWork work{5, {{false, false}, {false, true}}};
    loop.RunSeed(1, work, Frames(loop.Pipeline(), 1));
    CHECK(log.lines == std::vector<std::string>{"seed 1 5", "frame 0", "eye 1", "reference 1 hit",
                                                "output 1 two-history", "end 0", "end seed"});
    CHECK(loop.Pipeline().Config().run.seed == 5u);
}

TEST_CASE("without references the loop looks none up", "[loop]") {
    RunConfig config = test::SmallCornellConfig();
    config.denoise.denoisers = {"svgf"};
    FrameLoop loop(config, false);
    EventLog log;
    loop.Attach(log);
    loop.RunSeed(0, SeedWork{config.run.seed, {}}, Frames(loop.Pipeline(), 2));
    CHECK(log.lines == std::vector<std::string>{"seed 0 1", "frame 0", "eye 0", "output 0 svgf", "eye 1",
                                                "output 1 svgf", "end 0", "frame 1", "eye 0", "output 0 svgf",
                                                "eye 1", "output 1 svgf", "end 1", "end seed"});
    loop.Detach(log);
    log.lines.clear();
    loop.RunSeed(1, SeedWork{2, {}}, Frames(loop.Pipeline(), 1));
    CHECK(log.lines.empty());
}

TEST_CASE("warm-up frames advance the histories and nothing else", "[loop]") {
    // run.first_frame = 2 after 2 warm-up frames: the observers see frames 2 and 3 only, no
    // reference is looked up for 0 and 1, and the denoisers' outputs of 2 and 3 are those of a
    // run that scores every frame from 0: the warm-up frames were denoised.
    const fs::path dir = test::ScratchDir("fovrt_frame_loop_warmup_test");
    RunConfig config = test::SmallCornellConfig();
    config.denoise.denoisers = {"svgf"};
    config.reference.spp = 2;
    config.reference.cacheDir = (dir / "cache").string();
    class Outputs : public FrameLoopObserver {
    public:
        void Output(const StereoFrame& f, int eye, const DenoisedOutput& o) override {
            if (eye == 0) images.emplace_back(f.frame, *o.image);
        }
        std::vector<std::pair<uint32_t, Plane<vec3>>> images;
    };
    FrameLoop all(config, true);
    Outputs allOutputs;
    all.Attach(allOutputs);
    all.RunSeed(0, SeedWork{config.run.seed, {}}, Frames(all.Pipeline(), 4));
    REQUIRE(allOutputs.images.size() == 4);

    config.run.firstFrame = 2;
    config.run.warmupFrames = 2;
    FrameLoop warmed(config, true);
    EventLog log;
    Outputs warmedOutputs;
    warmed.Attach(log);
    warmed.Attach(warmedOutputs);
    warmed.RunSeed(0, SeedWork{config.run.seed, {}}, Frames(warmed.Pipeline(), 4));
    CHECK(log.lines == std::vector<std::string>{"seed 0 1", "frame 2", "eye 0", "reference 0 hit", "output 0 svgf",
                                                "eye 1", "reference 1 hit", "output 1 svgf", "end 2", "frame 3",
                                                "eye 0", "reference 0 hit", "output 0 svgf", "eye 1",
                                                "reference 1 hit", "output 1 svgf", "end 3", "end seed"});
    REQUIRE(warmedOutputs.images.size() == 2);
    for (size_t i = 0; i < 2; ++i) {
        CHECK(warmedOutputs.images[i].first == allOutputs.images[i + 2].first);
        CHECK(warmedOutputs.images[i].second.vector() == allOutputs.images[i + 2].second.vector());
    }
    // Without the warm-up frame 2 is a fresh history's first frame: it differs.
    RunConfig cold = config;
    cold.run.warmupFrames = 0;
    FrameLoop coldLoop(cold, false);
    Outputs coldOutputs;
    coldLoop.Attach(coldOutputs);
    coldLoop.RunSeed(0, SeedWork{cold.run.seed, {}}, [&, next = 2](FrameRequest& request) mutable {
        if (next >= 4) return false;
        request = coldLoop.Pipeline().RequestAt(uint32_t(next++));
        return true;
    });
    REQUIRE(coldOutputs.images.size() == 2);
    CHECK(coldOutputs.images[0].second.vector() != allOutputs.images[2].second.vector());
}
