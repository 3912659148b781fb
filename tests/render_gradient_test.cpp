// Re-shading (ProbeRenderer::Shade, render/probes.h) and A-SVGF gradient samples (paper §3): the
// forward-projected previous surface sample and its seed replace the pixel's own visibility-buffer
// entry and are shaded once, as every other pixel (no extra work). With nothing changing, that
// shading reproduces the old value exactly; switching the light off makes the difference large.
#include <cmath>
#include <cstring>

#include "core/rng.h"
#include "render/probes.h"
#include "render_test_scenes.h"
#include "test_support.h"

using namespace fovrt;
using namespace fovrt::test;

namespace {

constexpr int kW = 48, kH = 36;

Plane<uint16_t> RandomSppMap(uint32_t seed, int maxSpp) {
    Plane<uint16_t> map(kW, kH);
    Pcg32 rng(seed);
    for (size_t i = 0; i < map.size(); ++i) map[i] = uint16_t(1 + rng.NextBounded(uint32_t(maxSpp)));
    return map;
}

// Two frames of one eye; the spp maps differ between the frames, so a gradient pixel's previous
// sample count n_prev mostly differs from the map's n_cur.
struct TwoFrameRun {
    std::unique_ptr<ProbeRenderer> renderer;  // renders as CreateRenderer's (render_probes_test), and re-shades
    EyeCamera c0, c1;
    Plane<uint16_t> spp0, spp1;
    FrameInputs f0, f1;
    VisibilityBuffer v0, v1;  // the renderer's, copied after each frame
    RenderStats stats1;  // frame 1 only
};

TwoFrameRun RenderTwoFrames(const Scene& scene, bool gradients, const vec3& move = vec3(0.0f),
                            bool cut = false) {
    RenderSettings settings;
    settings.gradientSamples = gradients;
    settings.seed = 5;
    TwoFrameRun r;
    r.renderer = CreateProbeRenderer(scene, settings);
    Pose pose = scene.cameraPath.front().pose;
    r.c0 = MakeCamera(pose, kW, kH);
    pose.position += move;
    r.c1 = MakeCamera(pose, kW, kH);
    r.spp0 = RandomSppMap(7, 6);
    r.spp1 = RandomSppMap(8, 6);
    r.renderer->SetFrame(0);
    r.renderer->RenderEye(0, r.c0, r.c0, r.spp0, r.f0);
    r.v0 = r.renderer->Visibility(0);
    CHECK(r.f0.gradientSamples.empty());  // frame 0 has no history
    r.renderer->SetFrame(1);
    r.renderer->ResetStats();
    r.f1.cameraCut = cut;
    r.renderer->RenderEye(0, r.c1, r.c0, r.spp1, r.f1);
    r.v1 = r.renderer->Visibility(0);
    r.stats1 = r.renderer->Stats();
    // The old luminances are last frame's noisy colours at prevPixel.
    for (const GradientSample& g : r.f1.gradientSamples)
        REQUIRE(g.oldLuminance == Luminance(r.f0.NoisyColor(g.prevPixel.x, g.prevPixel.y)));
    return r;
}

std::vector<GradientSample> TwoFrames(const Scene& scene, FrameInputs& f1) {
    TwoFrameRun r = RenderTwoFrames(scene, true);
    f1 = std::move(r.f1);
    return f1.gradientSamples;
}

template <typename T>
bool SameBits(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

SurfaceSample VisibilityAt(const FrameInputs& f, const VisibilityBuffer& v, ivec2 p) {
    return SurfaceSample{f.objectId(p.x, p.y), v.primitiveId(p.x, p.y), v.barycentrics(p.x, p.y)};
}

}  // namespace

TEST_CASE("Shade() reproduces RenderEye's pixel colour exactly", "[render]") {
    Scene scene = BoxScene();
    auto renderer = CreateProbeRenderer(scene, RenderSettings{});
    EyeCamera camera = MakeCamera(scene.cameraPath.front().pose, kW, kH);
    Plane<uint16_t> spp(kW, kH, uint16_t(3));
    FrameInputs out;
    renderer->RenderEye(0, camera, camera, spp, out);
    const VisibilityBuffer& vis = renderer->Visibility(0);
    for (int y = 0; y < kH; y += 3)
        for (int x = 0; x < kW; x += 2) {
            SurfaceSample s{out.objectId(x, y), vis.primitiveId(x, y), vis.barycentrics(x, y)};
            vec3 c = renderer->Shade(camera, s, vis.seed(x, y), out.sampleCount(x, y));
            vec3 expected = out.NoisyColor(x, y);
            REQUIRE(std::memcmp(&c, &expected, sizeof(vec3)) == 0);
            vec3 p = renderer->WorldPosition(s);
            REQUIRE(std::memcmp(&p, &vis.worldPosition(x, y), sizeof(vec3)) == 0);
        }
}

TEST_CASE("static scene: every gradient sample has newLuminance == oldLuminance", "[render]") {
    TwoFrameRun r = RenderTwoFrames(BoxScene(), true);
    const std::vector<GradientSample>& samples = r.f1.gradientSamples;
    int strata = ((kW + 2) / 3) * ((kH + 2) / 3);
    // Static camera and scene: every stratum's pick lands in its own stratum.
    CHECK(int(samples.size()) == strata);
    std::vector<int> perStratum(size_t(strata), 0);
    Plane<uint8_t> isGradient(kW, kH, uint8_t(0));
    for (const GradientSample& g : samples) {
        REQUIRE(g.newLuminance == g.oldLuminance);
        REQUIRE(g.stratum == g.pixel / kGradientStratumSize);
        REQUIRE(g.pixel == g.prevPixel);
        REQUIRE(++perStratum[size_t(g.stratum.y * ((kW + 2) / 3) + g.stratum.x)] == 1);
        // Same surface, seed and n as last frame: the pixel's demodulated shading repeats bit
        // for bit, and it is the pixel's own sample of this frame.
        ivec2 p = g.pixel;
        REQUIRE(r.v1.seed(p.x, p.y) == r.v0.seed(p.x, p.y));
        REQUIRE(r.f1.sampleCount(p.x, p.y) == r.f0.sampleCount(p.x, p.y));
        REQUIRE(SameBits(r.f1.direct(p.x, p.y), r.f0.direct(p.x, p.y)));
        REQUIRE(SameBits(r.f1.indirect(p.x, p.y), r.f0.indirect(p.x, p.y)));
        REQUIRE(Luminance(r.f1.NoisyColor(p.x, p.y)) == g.newLuminance);
        isGradient(p.x, p.y) = 1;
    }
    // The other pixels use fresh seeds: their colours differ from last frame's.
    int others = 0, differing = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            if (isGradient(x, y)) continue;
            ++others;
            REQUIRE(r.v1.seed(x, y) != r.v0.seed(x, y));
            differing += Luminance(r.f1.NoisyColor(x, y)) != Luminance(r.f0.NoisyColor(x, y));
        }
    CHECK(differing > others / 2);
}

TEST_CASE("gradient samples replace pixel samples: traced samples = sum of sampleCount", "[render]") {
    TwoFrameRun r = RenderTwoFrames(BoxScene(), true, vec3(0.03f, 0.0f, 0.0f));
    REQUIRE(r.f1.gradientSamples.size() > 100);
    uint64_t recorded = 0, map = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            REQUIRE(r.f1.objectId(x, y) != kNoObject);  // closed room: every pixel shades its samples
            recorded += r.f1.sampleCount(x, y);
            map += r.spp1(x, y);
        }
    // No extra shading: every traced sample belongs to a pixel of the frame, one primary ray each.
    CHECK(r.stats1.samples == recorded);
    CHECK(r.stats1.primaryRays == uint64_t(kW * kH));
    // sampleCount differs from the spp map exactly at the gradient pixels, by n_prev - n_cur.
    int64_t expected = 0;
    int changed = 0;
    Plane<uint8_t> isGradient(kW, kH, uint8_t(0));
    for (const GradientSample& g : r.f1.gradientSamples) {
        int nPrev = r.f0.sampleCount(g.prevPixel.x, g.prevPixel.y), nCur = r.spp1(g.pixel.x, g.pixel.y);
        REQUIRE(r.f1.sampleCount(g.pixel.x, g.pixel.y) == nPrev);
        expected += nPrev - nCur;
        changed += nPrev != nCur;
        isGradient(g.pixel.x, g.pixel.y) = 1;
    }
    CHECK(changed > int(r.f1.gradientSamples.size()) / 2);  // the test distinguishes n_prev from n_cur
    CHECK(int64_t(recorded) - int64_t(map) == expected);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            if (!isGradient(x, y)) REQUIRE(r.f1.sampleCount(x, y) == r.spp1(x, y));
}

TEST_CASE("a gradient pixel is the re-shaded previous surface sample with its old seed", "[render]") {
    // Camera motion: the merged surface sample is not the pixel-centre one.
    TwoFrameRun r = RenderTwoFrames(BoxScene(), true, vec3(0.03f, 0.0f, 0.0f));
    REQUIRE(r.f1.gradientSamples.size() > 100);
    int offCentre = 0;
    for (const GradientSample& g : r.f1.gradientSamples) {
        ivec2 p = g.pixel, q = g.prevPixel;
        INFO("pixel " << p.x << "," << p.y << " from " << q.x << "," << q.y);
        SurfaceSample s = VisibilityAt(r.f0, r.v0, q);
        // The visibility-buffer entry, seed and sample count are the previous pixel's.
        REQUIRE(r.f1.objectId(p.x, p.y) == s.instance);
        REQUIRE(r.v1.primitiveId(p.x, p.y) == s.primitive);
        REQUIRE(SameBits(r.v1.barycentrics(p.x, p.y), s.barycentrics));
        REQUIRE(r.v1.seed(p.x, p.y) == r.v0.seed(q.x, q.y));
        REQUIRE(r.f1.sampleCount(p.x, p.y) == r.f0.sampleCount(q.x, q.y));
        vec3 position = r.renderer->WorldPosition(s);
        REQUIRE(SameBits(r.v1.worldPosition(p.x, p.y), position));
        REQUIRE(r.f1.linearDepth(p.x, p.y) == r.c1.LinearDepth(position));
        // Its colour is f_i(G→, ξ_{i−1}), bit for bit, and newLuminance is that colour's.
        vec3 reshaded = r.renderer->Shade(r.c1, s, r.v0.seed(q.x, q.y), r.f0.sampleCount(q.x, q.y));
        vec3 colour = r.f1.NoisyColor(p.x, p.y);
        REQUIRE(SameBits(reshaded, colour));
        REQUIRE(g.newLuminance == Luminance(colour));
        // Same surface point, same albedo: direct + indirect is the re-shaded illumination.
        REQUIRE(SameBits(r.f1.albedo(p.x, p.y), r.f0.albedo(q.x, q.y)));
        vec3 centre = r.c1.WorldDirection(vec2(p) + 0.5f);
        vec3 toSample = glm::normalize(position - r.c1.Position());
        offCentre += glm::dot(centre, toSample) < 1.0f - 1e-7f;
    }
    CHECK(offCentre > int(r.f1.gradientSamples.size()) / 2);
}

TEST_CASE("pixels without a gradient sample are as with gradient samples off", "[render]") {
    const vec3 move(0.03f, 0.0f, 0.0f);
    TwoFrameRun on = RenderTwoFrames(BoxScene(), true, move);
    TwoFrameRun off = RenderTwoFrames(BoxScene(), false, move);
    REQUIRE(off.f1.gradientSamples.empty());
    REQUIRE(on.f1.gradientSamples.size() > 100);
    Plane<uint8_t> isGradient(kW, kH, uint8_t(0));
    for (const GradientSample& g : on.f1.gradientSamples) isGradient(g.pixel.x, g.pixel.y) = 1;
    int merged = 0, mergedDiffering = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const FrameInputs &a = on.f1, &b = off.f1;
            const VisibilityBuffer &va = on.v1, &vb = off.v1;
            bool same = SameBits(a.direct(x, y), b.direct(x, y)) && SameBits(a.indirect(x, y), b.indirect(x, y)) &&
                        SameBits(a.albedo(x, y), b.albedo(x, y)) && SameBits(a.emission(x, y), b.emission(x, y)) &&
                        SameBits(a.normal(x, y), b.normal(x, y)) && SameBits(a.linearDepth(x, y), b.linearDepth(x, y)) &&
                        SameBits(a.depthGradient(x, y), b.depthGradient(x, y)) &&
                        a.objectId(x, y) == b.objectId(x, y) && SameBits(a.prevPixel(x, y), b.prevPixel(x, y)) &&
                        va.primitiveId(x, y) == vb.primitiveId(x, y) &&
                        SameBits(va.barycentrics(x, y), vb.barycentrics(x, y)) &&
                        SameBits(va.worldPosition(x, y), vb.worldPosition(x, y)) &&
                        a.sampleCount(x, y) == b.sampleCount(x, y) && va.seed(x, y) == vb.seed(x, y);
            if (isGradient(x, y)) {
                ++merged;
                mergedDiffering += !same;
            } else {
                INFO("pixel " << x << "," << y);
                REQUIRE(same);
            }
        }
    // Merged pixels hold the previous seed: they differ from the gradient-free render.
    CHECK(mergedDiffering == merged);
}

TEST_CASE("a light switched off gives large gradients", "[render]") {
    Scene scene = BoxScene(false, true);  // the point light is the only light
    Light& light = scene.lights[0];
    light.switchPeriod = 2.0f / scene.frameRate;  // on at frame 0, off at frame 1
    light.switchOnDuration = 0.5f / scene.frameRate;
    FrameInputs f1;
    std::vector<GradientSample> samples = TwoFrames(scene, f1);
    REQUIRE(samples.size() > 100);
    int large = 0, lit = 0;
    for (const GradientSample& g : samples) {
        CHECK(g.newLuminance == 0.0f);  // no light, no emission: black
        if (g.oldLuminance > 0.0f) {
            ++lit;
            large += std::abs(g.newLuminance - g.oldLuminance) / std::max(g.newLuminance, g.oldLuminance) > 0.99f;
        }
    }
    CHECK(lit > int(samples.size()) * 3 / 4);
    CHECK(large == lit);
}

TEST_CASE("camera motion forward-projects samples; cuts skip them", "[render]") {
    Scene scene = BoxScene();
    RenderSettings settings;
    settings.gradientSamples = true;
    auto renderer = CreateProbeRenderer(scene, settings);
    Pose pose0 = scene.cameraPath.front().pose;
    Pose pose1 = pose0;
    pose1.position += vec3(0.03f, 0.0f, 0.0f);
    EyeCamera c0 = MakeCamera(pose0, kW, kH), c1 = MakeCamera(pose1, kW, kH);
    Plane<uint16_t> spp(kW, kH, uint16_t(1));
    FrameInputs f0, f1;
    renderer->SetFrame(0);
    renderer->RenderEye(0, c0, c0, spp, f0);
    VisibilityBuffer v0 = renderer->Visibility(0);
    renderer->SetFrame(1);
    renderer->RenderEye(0, c1, c0, spp, f1);
    REQUIRE(f1.gradientSamples.size() > 50);
    int moved = 0;
    for (const GradientSample& g : f1.gradientSamples) {
        // The current pixel holds the projection of the previous sample's surface point.
        SurfaceSample s = VisibilityAt(f0, v0, g.prevPixel);
        auto proj = c1.Project(renderer->WorldPosition(s));
        REQUIRE(proj);
        CHECK(ivec2(glm::floor(proj->pixel)) == g.pixel);
        moved += g.pixel != g.prevPixel;
    }
    CHECK(moved > int(f1.gradientSamples.size()) / 2);
    // A camera cut: no gradient samples.
    renderer->SetFrame(2);
    FrameInputs f2;
    f2.cameraCut = true;
    renderer->RenderEye(0, c0, c1, spp, f2);
    CHECK(f2.gradientSamples.empty());
}
