// The probe renderer (render/probes.h): the same tracer over a recording scene renders exactly what
// the production renderer renders, and its ray log holds every ray the tracer traced.
#include <cstring>
#include <vector>

#include "render/probes.h"
#include "render_test_scenes.h"
#include "test_support.h"

using namespace fovrt;
using namespace fovrt::test;

namespace {

constexpr int kW = 45, kH = 37;  // odd: partial tiles and partial 8-wide packets

// Every FrameInputs plane's bytes, eye by eye, in ForEachPlane's order.
std::vector<unsigned char> PlaneBytesOf(const FrameInputs& f) {
    std::vector<unsigned char> out;
    f.ForEachPlane([&](const PlaneBytes& p) {
        const auto* bytes = static_cast<const unsigned char*>(p.data);
        out.insert(out.end(), bytes, bytes + p.bytes);
    });
    return out;
}

// Two frames (the second with A-SVGF gradient samples merged) of one eye, camera moving.
std::vector<FrameInputs> TwoFrames(Renderer& renderer, const Scene& scene) {
    Pose pose = scene.cameraPath.front().pose;
    EyeCamera c0 = MakeCamera(pose, kW, kH);
    pose.position += vec3(0.03f, 0.0f, 0.0f);
    EyeCamera c1 = MakeCamera(pose, kW, kH);
    Plane<uint16_t> spp(kW, kH);
    for (size_t i = 0; i < spp.size(); ++i) spp[i] = uint16_t(1 + i % 11);
    std::vector<FrameInputs> out(2);
    renderer.SetFrame(0);
    renderer.RenderEye(0, c0, c0, spp, out[0]);
    renderer.SetFrame(1);
    renderer.RenderEye(0, c1, c0, spp, out[1]);
    return out;
}

}  // namespace

TEST_CASE("the probe renderer renders bit-identically to the production renderer", "[render]") {
    Scene scene = BoxScene();
    for (int maxDepth : {1, 3}) {
        INFO("max depth " << maxDepth);
        RenderSettings settings;
        settings.maxDepth = maxDepth;
        settings.seed = 9;
        settings.gradientSamples = true;
        settings.fbetaPlane = true;
        auto production = CreateRenderer(scene, settings);
        auto probe = CreateProbeRenderer(scene, settings);
        std::vector<FrameInputs> a = TwoFrames(*production, scene), b = TwoFrames(*probe, scene);
        REQUIRE(b[1].gradientSamples.size() > 20);  // the merge ran
        for (size_t f = 0; f < a.size(); ++f) {
            REQUIRE(PlaneBytesOf(a[f]) == PlaneBytesOf(b[f]));
            REQUIRE(a[f].gradientSamples.size() == b[f].gradientSamples.size());
            for (size_t i = 0; i < a[f].gradientSamples.size(); ++i)
                REQUIRE(std::memcmp(&a[f].gradientSamples[i].newLuminance, &b[f].gradientSamples[i].newLuminance,
                                    sizeof(float)) == 0);
        }
        const RenderStats sa = production->Stats(), sb = probe->Stats();
        CHECK(sa.Rays() == sb.Rays());
        CHECK(sa.samples == sb.samples);
    }
}

TEST_CASE("the ray log holds every ray traced, and bare tracing finds the same primary hits", "[render]") {
    Scene scene = BoxScene();
    scene.instances.erase(scene.instances.begin());  // no room: the cube and the lamp against the background
    RenderSettings settings;
    settings.maxDepth = 2;
    auto renderer = CreateProbeRenderer(scene, settings);
    EyeCamera camera = MakeCamera(scene.cameraPath.front().pose, kW, kH);
    Plane<uint16_t> spp(kW, kH, uint16_t(3));
    FrameInputs out;
    std::vector<TracedRay> log;
    renderer->RecordRays(&log);
    renderer->RenderEye(0, camera, camera, spp, out);
    renderer->RecordRays(nullptr);
    const RenderStats stats = renderer->Stats();
    REQUIRE(log.size() == stats.Rays());
    size_t shadow = 0;
    for (const TracedRay& r : log) shadow += r.shadow ? 1 : 0;
    CHECK(shadow == stats.shadowRays - stats.shadowRaysReused);

    // The primary rays (from the eye, not shadow rays) hit exactly where the frame has an object.
    std::vector<TracedRay> primary;
    for (const TracedRay& r : log)
        if (!r.shadow && r.origin == camera.Position()) primary.push_back(r);
    REQUIRE(primary.size() == size_t(kW) * kH);
    uint64_t covered = 0;
    for (size_t i = 0; i < out.objectId.size(); ++i) covered += out.objectId[i] != kNoObject ? 1 : 0;
    CHECK(covered > 0);
    CHECK(covered < primary.size());  // the view sees some background
    CHECK(renderer->TraceBare(primary) == covered);

    // Stopped: the next frame adds nothing.
    renderer->RenderEye(0, camera, camera, spp, out);
    CHECK(log.size() == stats.Rays());
}
