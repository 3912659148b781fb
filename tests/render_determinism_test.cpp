// Determinism across thread counts, the spp map honoured exactly, and consistent ray counts.
#include <tbb/global_control.h>

#include "core/rng.h"
#include "render_test_scenes.h"
#include "test_support.h"

using namespace fovrt;
using namespace fovrt::test;

namespace {

// Odd size: partial tiles and partial 8-wide primary packets.
constexpr int kW = 45, kH = 37;

Plane<uint16_t> RandomSppMap(uint32_t seed) {
    Plane<uint16_t> map(kW, kH);
    Pcg32 rng(seed);
    for (size_t i = 0; i < map.size(); ++i) map[i] = uint16_t(1 + rng.NextBounded(16));
    return map;
}

struct Frames {
    FrameInputs f0, f1;
    VisibilityBuffer v0, v1;  // the renderer's, copied after each frame
    RenderStats stats;
};

Frames RenderTwoFrames(const Scene& scene, int threads, int maxDepth, const Plane<uint16_t>& spp) {
    RenderSettings settings;
    settings.threads = threads;
    settings.maxDepth = maxDepth;
    settings.seed = 42;
    settings.gradientSamples = true;
    auto renderer = CreateRenderer(scene, settings);
    EyeCamera camera = MakeCamera(scene.cameraPath.front().pose, kW, kH);
    Frames f;
    renderer->SetFrame(0);
    renderer->RenderEye(0, camera, camera, spp, f.f0);
    f.v0 = renderer->Visibility(0);
    renderer->SetFrame(1);
    renderer->RenderEye(0, camera, camera, spp, f.f1);
    f.v1 = renderer->Visibility(0);
    f.stats = renderer->Stats();
    return f;
}

void RequireBitIdentical(const FrameInputs& a, const FrameInputs& b) {
    CHECK(BitEqual(a.direct, b.direct));
    CHECK(BitEqual(a.indirect, b.indirect));
    CHECK(BitEqual(a.albedo, b.albedo));
    CHECK(BitEqual(a.emission, b.emission));
    CHECK(BitEqual(a.normal, b.normal));
    CHECK(BitEqual(a.linearDepth, b.linearDepth));
    CHECK(BitEqual(a.depthGradient, b.depthGradient));
    CHECK(BitEqual(a.objectId, b.objectId));
    CHECK(BitEqual(a.prevPixel, b.prevPixel));
    CHECK(BitEqual(a.sampleCount, b.sampleCount));
    REQUIRE(a.gradientSamples.size() == b.gradientSamples.size());
    for (size_t i = 0; i < a.gradientSamples.size(); ++i) {
        const GradientSample &x = a.gradientSamples[i], &y = b.gradientSamples[i];
        CHECK((x.pixel == y.pixel && x.prevPixel == y.prevPixel && x.stratum == y.stratum));
        CHECK(std::memcmp(&x.newLuminance, &y.newLuminance, sizeof(float)) == 0);
        CHECK(std::memcmp(&x.oldLuminance, &y.oldLuminance, sizeof(float)) == 0);
    }
}

void RequireBitIdentical(const VisibilityBuffer& a, const VisibilityBuffer& b) {
    CHECK(BitEqual(a.primitiveId, b.primitiveId));
    CHECK(BitEqual(a.barycentrics, b.barycentrics));
    CHECK(BitEqual(a.worldPosition, b.worldPosition));
    CHECK(BitEqual(a.seed, b.seed));
}

}  // namespace

TEST_CASE("FrameInputs are bit-identical for 1, 2 and 4 threads", "[render]") {
    // Allow 4 threads even on a 2-core machine (TBB caps workers at the core count otherwise).
    tbb::global_control allowFour(tbb::global_control::max_allowed_parallelism, 4);
    Scene scene = BoxScene();
    Plane<uint16_t> spp = RandomSppMap(3);
    Frames one = RenderTwoFrames(scene, 1, 2, spp);
    Frames two = RenderTwoFrames(scene, 2, 2, spp);
    Frames four = RenderTwoFrames(scene, 4, 2, spp);
    RequireBitIdentical(one.f0, two.f0);
    RequireBitIdentical(one.f1, two.f1);
    RequireBitIdentical(one.f0, four.f0);
    RequireBitIdentical(one.f1, four.f1);
    RequireBitIdentical(one.v0, two.v0);
    RequireBitIdentical(one.v1, two.v1);
    RequireBitIdentical(one.v0, four.v0);
    RequireBitIdentical(one.v1, four.v1);
    CHECK(!one.f1.gradientSamples.empty());
    CHECK(one.stats.Rays() == four.stats.Rays());
    // Different frames use different seeds, hence different noise.
    CHECK(!BitEqual(one.f0.direct, one.f1.direct));
    CHECK(!BitEqual(one.v0.seed, one.v1.seed));
}

TEST_CASE("the spp map is honoured exactly and rays are counted consistently", "[render]") {
    // Closed room, Lambert walls, one point light inside and nothing else: every sample casts
    // exactly one shadow ray per vertex, every bounce hits a wall.
    Scene scene = BoxScene(false, true);
    scene.instances.erase(scene.instances.begin() + 1);  // no cube
    Plane<uint16_t> spp = RandomSppMap(11);
    uint64_t expectedSamples = 0;
    for (size_t i = 0; i < spp.size(); ++i) expectedSamples += spp[i];
    for (int maxDepth : {1, 2}) {
        RenderSettings settings;
        settings.maxDepth = maxDepth;
        auto renderer = CreateRenderer(scene, settings);
        EyeCamera camera = MakeCamera(scene.cameraPath.front().pose, kW, kH);
        FrameInputs out;
        renderer->RenderEye(0, camera, camera, spp, out);
        REQUIRE(BitEqual(out.sampleCount, spp));
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                REQUIRE(out.objectId(x, y) == 0u);
                REQUIRE(renderer->Visibility(0).seed(x, y) == PixelSeed(settings.seed, 0, uint32_t(x), uint32_t(y), 0));
            }
        RenderStats s = renderer->Stats();
        INFO("maxDepth " << maxDepth << " shadow " << s.shadowRays << " bounce " << s.bounceRays);
        CHECK(s.primaryRays == uint64_t(kW * kH));
        CHECK(s.samples == expectedSamples);
        CHECK(s.droppedSamples == 0);
        if (maxDepth == 1) {
            CHECK(s.bounceRays == 0);
            CHECK(s.shadowRays == expectedSamples);
        } else {
            CHECK(s.bounceRays <= expectedSamples);
            CHECK(s.bounceRays > expectedSamples * 9 / 10);
            CHECK(s.shadowRays == expectedSamples + s.bounceRays);
        }
        renderer->ResetStats();
        CHECK(renderer->Stats().Rays() == 0);
    }
}

TEST_CASE("more samples per pixel reduce the noise", "[render]") {
    Scene scene = BoxScene();
    RenderSettings settings;
    auto renderer = CreateRenderer(scene, settings);
    EyeCamera camera = MakeCamera(scene.cameraPath.front().pose, kW, kH);
    Plane<vec3> reference;
    renderer->RenderReference(0, camera, 256, 1u, reference);
    auto error = [&](int n) {
        FrameInputs out;
        renderer->RenderEye(0, camera, camera, Plane<uint16_t>(kW, kH, uint16_t(n)), out);
        double e = 0.0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                float d = Luminance(out.NoisyColor(x, y) - reference(x, y));
                e += double(d) * d;
            }
        return e;
    };
    double e1 = error(1), e16 = error(16);
    INFO("squared error at 1 spp " << e1 << ", at 16 spp " << e16);
    CHECK(e16 < e1 / 4.0);
}
