// Pixels the spp map gives 0 samples (a periphery below 1 spp): the tracer still traces their
// primary ray for the guide planes (counted as guide rays, apart from the path samples), leaves
// their colour at 0 and records n = 0; A-SVGF's forward projection draws no gradient sample from a
// pixel that had no path sample.
#include <cmath>
#include <cstring>

#include "render/probes.h"
#include "render_test_scenes.h"
#include "test_support.h"

using namespace fovrt;
using namespace fovrt::test;

namespace {

constexpr int kW = 48, kH = 36;

// 0 at every 4th pixel of a 2×2-interleaved pattern that moves with the frame; 3 elsewhere.
Plane<uint16_t> QuarterZeroSppMap(uint32_t frame) {
    Plane<uint16_t> map(kW, kH, uint16_t(3));
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            if (((x & 1) + 2 * (y & 1)) == int(frame % 4)) map(x, y) = 0;
    return map;
}

template <typename T>
bool SameBits(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

}  // namespace

TEST_CASE("a 0-spp pixel gets its guide planes and a guide ray, colour 0", "[render]") {
    const Scene scene = BoxScene();
    const EyeCamera camera = MakeCamera(scene.cameraPath.front().pose, kW, kH);
    auto renderer = CreateRenderer(scene, RenderSettings{});
    const Plane<uint16_t> zeros = QuarterZeroSppMap(1), ones(kW, kH, uint16_t(1));
    FrameInputs sparse, full;
    renderer->RenderEye(0, camera, camera, zeros, sparse);
    const RenderStats stats = renderer->Stats();
    renderer->ResetStats();
    renderer->RenderEye(0, camera, camera, ones, full);
    const RenderStats fullStats = renderer->Stats();

    uint64_t zeroPixels = 0, mapSamples = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            mapSamples += zeros(x, y);
            REQUIRE(sparse.sampleCount(x, y) == zeros(x, y));
            // Primary visibility is noise-free: the guide planes do not depend on n.
            REQUIRE(sparse.objectId(x, y) == full.objectId(x, y));
            REQUIRE(SameBits(sparse.normal(x, y), full.normal(x, y)));
            REQUIRE(SameBits(sparse.linearDepth(x, y), full.linearDepth(x, y)));
            REQUIRE(SameBits(sparse.depthGradient(x, y), full.depthGradient(x, y)));
            REQUIRE(SameBits(sparse.prevPixel(x, y), full.prevPixel(x, y)));
            REQUIRE(SameBits(sparse.albedo(x, y), full.albedo(x, y)));
            REQUIRE(SameBits(sparse.emission(x, y), full.emission(x, y)));
            REQUIRE(SameBits(sparse.roughness(x, y), full.roughness(x, y)));
            if (zeros(x, y) != 0) continue;
            ++zeroPixels;
            REQUIRE(sparse.objectId(x, y) != kNoObject);  // closed room: every guide is a surface
            REQUIRE(sparse.direct(x, y) == vec3(0.0f));
            REQUIRE(sparse.indirect(x, y) == vec3(0.0f));
        }
    REQUIRE(zeroPixels == uint64_t(kW * kH / 4));
    CHECK(stats.primaryRays == uint64_t(kW * kH));
    CHECK(stats.guideRays == zeroPixels);
    CHECK(stats.samples == mapSamples);
    CHECK(fullStats.guideRays == 0);
    CHECK(stats.droppedSamples == 0);
}

TEST_CASE("no A-SVGF gradient sample comes from a pixel without path samples", "[render]") {
    const Scene scene = BoxScene();
    RenderSettings settings;
    settings.gradientSamples = true;
    auto renderer = CreateRenderer(scene, settings);
    const EyeCamera camera = MakeCamera(scene.cameraPath.front().pose, kW, kH);
    FrameInputs prev, cur;
    const Plane<uint16_t> map0 = QuarterZeroSppMap(0), map1 = QuarterZeroSppMap(1);
    renderer->SetFrame(0);
    renderer->RenderEye(0, camera, camera, map0, prev);
    renderer->SetFrame(1);
    renderer->RenderEye(0, camera, camera, map1, cur);
    // Static view: every 3×3 stratum had pixels with samples, so every one still has its sample.
    const int strata = ((kW + 2) / 3) * ((kH + 2) / 3);
    CHECK(int(cur.gradientSamples.size()) == strata);
    for (const GradientSample& g : cur.gradientSamples) {
        INFO("pixel " << g.pixel.x << "," << g.pixel.y << " from " << g.prevPixel.x << ","
                      << g.prevPixel.y);
        REQUIRE(prev.sampleCount(g.prevPixel.x, g.prevPixel.y) > 0);
        REQUIRE(cur.sampleCount(g.pixel.x, g.pixel.y) ==
                prev.sampleCount(g.prevPixel.x, g.prevPixel.y));
        REQUIRE(g.newLuminance == g.oldLuminance);  // same scene, same seed and n: a zero gradient
    }
}
