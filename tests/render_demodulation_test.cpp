// render.demodulation (SPEC §6, issue #13): the tracer divides direct and indirect by the
// primary hit's F_β instead of its albedo, writes the F_β plane under albedo demodulation only
// when asked (and nothing else changes), and the noisy colour is the same under both; a
// pure-Lambert scene's FrameInputs do not change at all; under a uniform sky a rough/smooth
// metal's direct light divided by F_β is 1 while its radiance is not.
#include <algorithm>
#include <cmath>

#include "render/brdf_table.h"
#include "render_test_scenes.h"
#include "test_support.h"

using namespace fovrt;
using namespace fovrt::test;

namespace {

FrameInputs RenderOnce(const Scene& scene, Demodulation d, const EyeCamera& camera, int spp,
                       bool fbetaPlane = true) {
    RenderSettings settings;
    settings.seed = 11;
    settings.demodulation = d;
    settings.fbetaPlane = fbetaPlane;
    auto renderer = CreateRenderer(scene, settings);
    Plane<uint16_t> sppMap(camera.width(), camera.height(), uint16_t(spp));
    FrameInputs out;
    renderer->RenderEye(0, camera, camera, sppMap, out);
    return out;
}

EyeCamera SceneCamera(const Scene& scene, int w, int h) {
    return MakeCamera(scene.HeadAt(0.0f), w, h, scene.horizontalFovDegrees);
}

// Max over pixels and channels of |a − b| / max(|a|, |b|, 1e-20).
double MaxRelative(const Plane<vec3>& a, const Plane<vec3>& b) {
    double worst = 0.0;
    for (size_t i = 0; i < a.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            double x = a[i][c], y = b[i][c];
            double scale = std::max({std::fabs(x), std::fabs(y), 1e-20});
            worst = std::max(worst, std::fabs(x - y) / scale);
        }
    return worst;
}

void CheckSameNoisyColour(const Scene& scene, const EyeCamera& camera, int spp, bool lambertOnly) {
    const FrameInputs a = RenderOnce(scene, Demodulation::Albedo, camera, spp);
    const FrameInputs b = RenderOnce(scene, Demodulation::Brdf, camera, spp);
    CHECK(a.demodulation == Demodulation::Albedo);
    CHECK(b.demodulation == Demodulation::Brdf);
    // The factor planes and the geometry do not depend on the choice.
    CHECK(BitEqual(a.albedo, b.albedo));
    CHECK(BitEqual(a.fbeta, b.fbeta));
    CHECK(BitEqual(a.emission, b.emission));
    CHECK(BitEqual(a.normal, b.normal));
    CHECK(BitEqual(a.linearDepth, b.linearDepth));
    const double rel = MaxRelative(a.NoisyImage(), b.NoisyImage());
    INFO(scene.name << ": max relative difference of the remodulated noisy colour " << rel);
    CHECK(rel <= 1e-6);
    // The two demodulated signals differ by the ratio of the factors where they differ.
    size_t differing = 0;
    for (size_t i = 0; i < a.albedo.size(); ++i) differing += a.albedo[i] != a.fbeta[i] ? 1 : 0;
    // cornell is all Lambert (its MTL has Ks 0): there F_β is the albedo.
    if (lambertOnly) CHECK(differing == 0);
    else CHECK(differing > 0);
}

}  // namespace

TEST_CASE("remodulated noisy colour is the same under albedo and brdf demodulation", "[render]") {
    const Scene box = BoxScene();
    CheckSameNoisyColour(box, MakeCamera(box.HeadAt(0.0f), 48, 32), 4, false);
    for (const char* name : {"cornell", "brdf-detail"}) {
        const Scene scene = LoadScene(ResolveSceneName(name));
        CheckSameNoisyColour(scene, SceneCamera(scene, 64, 36), 2, std::string(name) == "cornell");
    }
}

TEST_CASE("without a +brdf variant the F_beta plane is 0 and every other plane is unchanged", "[render]") {
    const Scene scene = LoadScene(ResolveSceneName("brdf-detail"));
    const EyeCamera camera = SceneCamera(scene, 64, 36);
    const FrameInputs on = RenderOnce(scene, Demodulation::Albedo, camera, 2, true);
    const FrameInputs off = RenderOnce(scene, Demodulation::Albedo, camera, 2, false);
    size_t surface = 0;
    for (size_t i = 0; i < on.fbeta.size(); ++i) {
        if (on.objectId[i] == kNoObject) continue;
        ++surface;
        CHECK(glm::all(glm::greaterThanEqual(on.fbeta[i], vec3(1e-3f))));
    }
    REQUIRE(surface > 1000);
    CHECK(BitEqual(off.fbeta, Plane<vec3>(64, 36, vec3(0.0f))));
    // Brdf demodulation fills it whatever the setting says.
    CHECK(BitEqual(RenderOnce(scene, Demodulation::Brdf, camera, 2, false).fbeta, on.fbeta));
    on.VisitPlanes([&](const PlaneSpec& spec, const auto& plane) {
        off.VisitPlanes([&](const PlaneSpec& other, const auto& otherPlane) {
            if constexpr (std::is_same_v<std::decay_t<decltype(plane)>, std::decay_t<decltype(otherPlane)>>) {
                if (std::string(spec.name) != other.name || std::string(spec.name) == "fbeta") return;
                INFO("plane " << spec.name);
                CHECK(BitEqual(plane, otherPlane));
            }
        });
    });
}

TEST_CASE("a pure-Lambert scene gives identical FrameInputs under both demodulations", "[render]") {
    Scene scene = BoxScene();
    scene.name = "lambert";
    for (Material& m : scene.materials) {
        m.metallic = 0.0f;
        m.specular = 0.0f;  // F0 = 0: the BSDF is Lambert, F_β = d = the albedo
    }
    const EyeCamera camera = MakeCamera(scene.HeadAt(0.0f), 48, 32);
    const FrameInputs a = RenderOnce(scene, Demodulation::Albedo, camera, 4);
    const FrameInputs b = RenderOnce(scene, Demodulation::Brdf, camera, 4);
    bool allEqual = true;
    a.VisitPlanes([&](const PlaneSpec& spec, const auto& plane) {
        b.VisitPlanes([&](const PlaneSpec& other, const auto& otherPlane) {
            if constexpr (std::is_same_v<std::decay_t<decltype(plane)>, std::decay_t<decltype(otherPlane)>>) {
                if (std::string(spec.name) != other.name) return;
                const bool equal = BitEqual(plane, otherPlane);
                INFO("plane " << spec.name);
                CHECK(equal);
                allEqual = allEqual && equal;
            }
        });
    });
    CHECK(allEqual);
    CHECK(BitEqual(a.albedo, a.fbeta));
}

TEST_CASE("sky furnace: a metal with a roughness map has direct / F_beta = 1 while its radiance varies", "[render]") {
    // A flat metal quad under a uniform white sky, nothing else: every reflected ray sees the
    // sky, so direct light = ∫ f cos dω = F_β at each pixel's (μ, roughness) and indirect = 0.
    Scene s;
    s.name = "sky-furnace";
    s.background = vec3(1.0f);
    Material metal;
    metal.baseColor = vec3(0.95f, 0.64f, 0.54f);
    metal.metallic = 1.0f;
    metal.roughness = 1.0f;
    metal.roughnessTexture = 0;
    s.materials.push_back(metal);
    Texture map;  // 8 × 8 cells: roughness 0.1 / 0.8
    map.width = map.height = 8;
    for (int i = 0; i < 64; ++i) {
        float r = ((i % 8) + (i / 8)) % 2 ? 0.8f : 0.1f;
        map.texels.push_back(vec4(r, r, r, 1.0f));
    }
    s.textures.push_back(map);
    Mesh quad;
    quad.name = "quad";
    AddQuad(quad, vec3(0.0f), vec3(1, 0, 0), vec3(0, 0, -1), 0);  // y = 0, facing +y
    s.meshes.push_back(quad);
    s.instances.push_back(Instance{"quad", 0, {}, false});
    s.cameraPath.push_back(CameraKey{0.0f, Pose::LookAt(vec3(0, 1.2f, 1.2f), vec3(0, 0, 0))});
    const EyeCamera camera = MakeCamera(s.HeadAt(0.0f), 32, 32, 50.0f);
    const FrameInputs f = RenderOnce(s, Demodulation::Brdf, camera, 256);
    float lo = 1e30f, hi = 0.0f, radianceLo = 1e30f, radianceHi = 0.0f;
    int pixels = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            if (f.objectId(x, y) == kNoObject) continue;
            ++pixels;
            CHECK(f.indirect(x, y) == vec3(0.0f));
            for (int c = 0; c < 3; ++c) {
                lo = std::min(lo, f.direct(x, y)[c]);
                hi = std::max(hi, f.direct(x, y)[c]);
            }
            const float radiance = Luminance(f.NoisyColor(x, y));
            radianceLo = std::min(radianceLo, radiance);
            radianceHi = std::max(radianceHi, radiance);
        }
    INFO("pixels " << pixels << ": direct / F_beta in [" << lo << ", " << hi << "], radiance in [" << radianceLo
                   << ", " << radianceHi << "]");
    REQUIRE(pixels > 500);
    CHECK(lo >= 0.99f);
    CHECK(hi <= 1.01f);
    CHECK(radianceHi > 1.15f * radianceLo);  // the roughness map shows in the radiance
}
