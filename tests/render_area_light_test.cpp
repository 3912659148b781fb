// One-sided area lights (issue #16): an emissive triangle emits only to the side of its geometric
// normal unless its material is two-sided, for every estimator alike (camera rays, NEE and
// BSDF-sampled hits, MIS-weighted), and a two-sided one emits the same radiance from both sides.
#include <cmath>

#include "render_test_scenes.h"
#include "test_support.h"

using namespace fovrt;
using namespace fovrt::test;

namespace {

constexpr float kAlbedo = 0.5f, kLe = 2.0f, kHalf = 0.5f, kHeight = 1.0f;

// A Lambert receiver quad at y = 0 facing up, a square light A (side 2·kHalf) kHeight above it,
// facing down or up, and a one-sided light B beside it facing up: the receiver is behind B, which
// takes a share of the light-selection power but must add nothing.
Scene QuadLightScene(bool lightFacesDown, bool twoSided) {
    Scene s;
    s.name = "quad-light";
    Material receiver, lightA, lightB;
    receiver.baseColor = vec3(kAlbedo);
    receiver.specular = 0.0f;  // pure Lambert: albedo = base colour
    lightA.baseColor = lightB.baseColor = vec3(0.0f);  // black: no light bounces off the panels
    lightA.emission = lightB.emission = vec3(kLe);
    lightA.emissionTwoSided = twoSided;
    s.materials = {receiver, lightA, lightB};
    Mesh m;
    m.name = "stage";
    AddQuad(m, vec3(0.0f), vec3(0, 0, kHalf), vec3(kHalf, 0, 0), 0);  // normal +y
    const vec3 x(kHalf, 0, 0), z(0, 0, kHalf);
    if (lightFacesDown) AddQuad(m, vec3(0, kHeight, 0), x, z, 1);  // cross(x, z) = -y
    else AddQuad(m, vec3(0, kHeight, 0), z, x, 1);
    AddQuad(m, vec3(3, kHeight, 0), z, x, 2);  // faces up, away from the receiver
    s.meshes.push_back(m);
    s.instances.push_back(Instance{"stage", 0, {}, false});
    s.background = vec3(0.0f);
    s.cameraPath.push_back(CameraKey{});
    return s;
}

// Irradiance / Le at a point under the centre of a parallel square (side 2a at height h): four
// times the form factor from a point to a parallel rectangle above its corner, times pi.
double SquareIrradianceOverLe(double a, double h) {
    double x = a / h, r = std::sqrt(1.0 + x * x);
    double cornerFormFactor = (x / r) * std::atan(x / r) / kPi;  // X = Y: the two terms are equal
    return kPi * 4.0 * cornerFormFactor;
}

struct Frame {
    vec3 meanColour = vec3(0.0f), meanEmission = vec3(0.0f);
    uint32_t centreObject = kNoObject;
    float centreDepth = 0.0f;
    vec3 centreAlbedo = vec3(0.0f);
};

Frame Render(const Scene& scene, const Pose& pose, int maxDepth, int spp, float hfovDeg) {
    RenderSettings settings;
    settings.maxDepth = maxDepth;
    settings.seed = 5;
    auto renderer = CreateRenderer(scene, settings);
    const int w = 8, h = 8;
    EyeCamera camera = MakeCamera(pose, w, h, hfovDeg);
    Plane<uint16_t> sppMap(w, h, uint16_t(spp));
    FrameInputs out;
    renderer->RenderEye(0, camera, camera, sppMap, out);
    CHECK(renderer->Stats().droppedSamples == 0);
    Frame f;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            f.meanColour += out.NoisyColor(x, y) / float(w * h);
            f.meanEmission += out.emission(x, y) / float(w * h);
        }
    f.centreObject = out.objectId(w / 2, h / 2);
    f.centreDepth = out.linearDepth(w / 2, h / 2);
    f.centreAlbedo = out.albedo(w / 2, h / 2);
    return f;
}

// A narrow view of the receiver's centre (footprint ~1 cm, where the irradiance is flat).
const Pose kOnReceiver = Pose::LookAt(vec3(0.0f, 0.5f, 0.5f), vec3(0.0f));
// Between receiver and light, looking up at light A's centre.
const Pose kOnLight = Pose::LookAt(vec3(0.0f, 0.5f, 0.0f), vec3(0.0f, kHeight, 0.0f), vec3(0, 0, -1));

}  // namespace

TEST_CASE("a quad light lights only its front side unless it is two-sided", "[render]") {
    const double expected = kAlbedo / kPi * kLe * SquareIrradianceOverLe(kHalf, kHeight);
    INFO("closed form: reflected radiance " << expected);
    struct Case {
        const char* what;
        bool facesDown, twoSided;
        double radiance, seenEmission;
    };
    for (const Case& c : {Case{"one-sided, facing the receiver", true, false, expected, kLe},
                          Case{"one-sided, facing away", false, false, 0.0, 0.0},
                          Case{"two-sided, facing away", false, true, expected, kLe}}) {
        Scene scene = QuadLightScene(c.facesDown, c.twoSided);
        // maxDepth 1: NEE alone (full weight); 2: NEE and BSDF-sampled hits of the light, MIS-weighted.
        for (int depth = 1; depth <= 2; ++depth) {
            Frame f = Render(scene, kOnReceiver, depth, 256, 1.0f);
            INFO(c.what << ", maxDepth " << depth << ": reflected " << f.meanColour.x);
            if (c.radiance == 0.0) CHECK(f.meanColour == vec3(0.0f));  // not merely small
            else for (int k = 0; k < 3; ++k) CHECK(f.meanColour[k] == Approx(c.radiance).epsilon(0.01));
        }
        // The camera sees the light's emission from below only where it emits downwards.
        Frame seen = Render(scene, kOnLight, 1, 1, 10.0f);
        INFO(c.what << ": emission seen from below " << seen.meanEmission.x);
        CHECK(seen.meanEmission == vec3(float(c.seenEmission)));
    }
}

TEST_CASE("the built-in Cornell box's light faces down and leaves the ceiling above it unlit", "[render]") {
    Scene scene = LoadScene(SourceDir() / "scenes" / "cornell.toml");
    // The ceiling is at y = 2, the light 2 cm below it: look up at the ceiling from the gap.
    const Pose ceiling = Pose::LookAt(vec3(0.0f, 1.99f, 0.0f), vec3(0.0f, 2.0f, 0.0f), vec3(0, 0, -1));
    const Pose floor = Pose::LookAt(vec3(0.0f, 1.0f, 0.0f), vec3(0.0f), vec3(0, 0, -1));
    // maxDepth 1: direct light only, and the area light is the scene's only light.
    Frame above = Render(scene, ceiling, 1, 16, 20.0f);
    // The view is of the ceiling (the room's white, 1 cm away), not of the light's back.
    CHECK(above.centreObject == 0u);
    CHECK(above.centreDepth == Approx(0.01f).epsilon(0.01));
    CHECK(above.centreAlbedo.x == Approx(0.73f));
    CHECK(above.meanColour == vec3(0.0f));
    CHECK(Luminance(Render(scene, floor, 1, 16, 20.0f).meanColour) > 0.01f);
    // With a two-sided light the same view is lit (after the shadow-ray fix: before, the light's
    // own plane occluded these grazing shadow rays).
    for (Material& m : scene.materials) m.emissionTwoSided = true;
    float lit = Luminance(Render(scene, ceiling, 1, 16, 20.0f).meanColour);
    INFO("ceiling above a two-sided light: luminance " << lit);
    CHECK(lit > 0.01f);
}
