// Re-shading API and A-SVGF gradient samples (paper §3): with nothing changing, re-shading the
// forward-projected previous sample with its previous seed reproduces the old value exactly;
// switching the light off makes the difference large.
#include <cmath>

#include "render_test_scenes.h"
#include "test_support.h"

using namespace fovrt;
using namespace fovrt::test;

namespace {

constexpr int kW = 48, kH = 36;

std::vector<GradientSample> TwoFrames(const Scene& scene, FrameInputs& f1, bool cut = false) {
    RenderSettings settings;
    settings.gradientSamples = true;
    settings.seed = 5;
    auto renderer = CreateRenderer(scene, settings);
    EyeCamera camera = MakeCamera(scene.cameraPath.front().pose, kW, kH);
    Plane<uint16_t> spp(kW, kH, uint16_t(2));
    for (int x = 0; x < kW; ++x) spp(x, 5) = 7;  // mixed counts: re-shading must reuse them
    FrameInputs f0;
    renderer->SetFrame(0);
    renderer->RenderEye(0, camera, camera, spp, f0);
    CHECK(f0.gradientSamples.empty());  // frame 0 has no history
    renderer->SetFrame(1);
    f1.cameraCut = cut;
    renderer->RenderEye(0, camera, camera, spp, f1);
    // The old luminances are last frame's noisy colours at prevPixel.
    for (const GradientSample& g : f1.gradientSamples)
        REQUIRE(g.oldLuminance == Luminance(f0.NoisyColor(g.prevPixel.x, g.prevPixel.y)));
    return f1.gradientSamples;
}

}  // namespace

TEST_CASE("Shade() reproduces RenderEye's pixel colour exactly", "[render]") {
    Scene scene = BoxScene();
    auto renderer = CreateRenderer(scene, RenderSettings{});
    EyeCamera camera = MakeCamera(scene.cameraPath.front().pose, kW, kH);
    Plane<uint16_t> spp(kW, kH, uint16_t(3));
    FrameInputs out;
    renderer->RenderEye(0, camera, camera, spp, out);
    for (int y = 0; y < kH; y += 3)
        for (int x = 0; x < kW; x += 2) {
            SurfaceSample s{out.objectId(x, y), out.primitiveId(x, y), out.barycentrics(x, y)};
            vec3 c = renderer->Shade(camera, s, out.seed(x, y), out.sampleCount(x, y));
            vec3 expected = out.NoisyColor(x, y);
            REQUIRE(std::memcmp(&c, &expected, sizeof(vec3)) == 0);
            vec3 p = renderer->WorldPosition(s);
            REQUIRE(std::memcmp(&p, &out.worldPosition(x, y), sizeof(vec3)) == 0);
        }
}

TEST_CASE("static scene: every gradient sample has newLuminance == oldLuminance", "[render]") {
    FrameInputs f1;
    std::vector<GradientSample> samples = TwoFrames(BoxScene(), f1);
    int strata = ((kW + 2) / 3) * ((kH + 2) / 3);
    // Static camera and scene: every stratum's pick lands in its own stratum.
    CHECK(int(samples.size()) == strata);
    std::vector<int> perStratum(size_t(strata), 0);
    for (const GradientSample& g : samples) {
        REQUIRE(g.newLuminance == g.oldLuminance);
        REQUIRE(g.stratum == g.pixel / kGradientStratumSize);
        REQUIRE(g.pixel == g.prevPixel);
        REQUIRE(++perStratum[size_t(g.stratum.y * ((kW + 2) / 3) + g.stratum.x)] == 1);
    }
    // The re-shaded frame itself uses fresh seeds: its own colours differ from the old ones.
    int differing = 0;
    for (const GradientSample& g : samples)
        differing += Luminance(f1.NoisyColor(g.pixel.x, g.pixel.y)) != g.oldLuminance;
    CHECK(differing > int(samples.size()) / 2);
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
    auto renderer = CreateRenderer(scene, settings);
    Pose pose0 = scene.cameraPath.front().pose;
    Pose pose1 = pose0;
    pose1.position += vec3(0.03f, 0.0f, 0.0f);
    EyeCamera c0 = MakeCamera(pose0, kW, kH), c1 = MakeCamera(pose1, kW, kH);
    Plane<uint16_t> spp(kW, kH, uint16_t(1));
    FrameInputs f0, f1;
    renderer->SetFrame(0);
    renderer->RenderEye(0, c0, c0, spp, f0);
    renderer->SetFrame(1);
    renderer->RenderEye(0, c1, c0, spp, f1);
    REQUIRE(f1.gradientSamples.size() > 50);
    int moved = 0;
    for (const GradientSample& g : f1.gradientSamples) {
        // The current pixel holds the projection of the previous sample's surface point.
        SurfaceSample s{f0.objectId(g.prevPixel.x, g.prevPixel.y), f0.primitiveId(g.prevPixel.x, g.prevPixel.y),
                        f0.barycentrics(g.prevPixel.x, g.prevPixel.y)};
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
