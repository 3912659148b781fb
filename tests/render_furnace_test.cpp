// White furnace: the camera sits at the centre of a closed sphere whose inside emits Le and
// reflects with albedo a. Counting the emission seen at the primary hit as k = 0, a path tracer
// with maxDepth d must return Le * sum_{k=0..d} a^k (SPEC §2; renderer.h depth convention).
#include <cmath>

#include "ggx_quadrature.h"
#include "render/bsdf.h"
#include "render_test_scenes.h"
#include "test_support.h"

using namespace fovrt;
using namespace fovrt::test;

namespace {

// Mean remodulated colour over a small image looking from the sphere's centre.
vec3 FurnaceMean(const Scene& scene, int maxDepth, int spp, vec3* minOut = nullptr, vec3* maxOut = nullptr) {
    RenderSettings settings;
    settings.maxDepth = maxDepth;
    settings.seed = 7;
    auto renderer = CreateRenderer(scene, settings);
    EyeCamera camera = MakeCamera(Pose::LookAt(vec3(0.0f), vec3(0.3f, 0.2f, -1.0f)), 16, 16, 90.0f);
    Plane<uint16_t> sppMap(16, 16, uint16_t(spp));
    FrameInputs out;
    renderer->RenderEye(0, camera, camera, sppMap, out);
    vec3 sum(0.0f), lo(1e30f), hi(-1e30f);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            REQUIRE(out.objectId(x, y) == 0u);
            vec3 c = out.NoisyColor(x, y);
            sum += c;
            lo = glm::min(lo, c);
            hi = glm::max(hi, c);
        }
    if (minOut) *minOut = lo;
    if (maxOut) *maxOut = hi;
    CHECK(renderer->Stats().droppedSamples == 0);
    return sum / 256.0f;
}

}  // namespace

TEST_CASE("Lambert white furnace matches Le * sum a^k for each max depth", "[render]") {
    const float a = 0.6f;
    const vec3 le(1.0f, 0.5f, 2.0f);
    Scene scene = FurnaceScene(vec3(a), le, 1.0f, 0.0f, 0.0f);  // specular 0: pure Lambert
    for (int depth = 1; depth <= 3; ++depth) {
        float series = 0.0f;
        for (int k = 0; k <= depth; ++k) series += std::pow(a, float(k));
        vec3 mean = FurnaceMean(scene, depth, 8);
        INFO("maxDepth " << depth << " mean " << mean.x << " " << mean.y << " " << mean.z);
        for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(le[c] * series).epsilon(0.01));
    }
}

TEST_CASE("GGX conductor furnace: energy <= 1 and close to the integrated albedo", "[render]") {
    const vec3 le(1.0f);
    const float roughness = 0.3f;
    double albedo = GgxAlbedoNormalIncidence(double(roughness) * roughness);
    INFO("GGX albedo at normal incidence " << albedo);
    REQUIRE(albedo <= 1.0);
    REQUIRE(albedo > 0.95);
    // metallic = 1 with base colour 1 gives F0 = 1, i.e. Fresnel = 1 everywhere.
    Scene scene = FurnaceScene(vec3(1.0f), le, roughness, 1.0f, 1.0f);
    vec3 lo, hi;
    vec3 mean = FurnaceMean(scene, 2, 16, &lo, &hi);
    double expected = 1.0 + albedo + albedo * albedo;
    INFO("mean " << mean.x << " expected " << expected << " max pixel " << hi.x);
    CHECK(mean.x == Approx(expected).epsilon(0.02));
    CHECK(mean.x <= 3.0f * 1.005f);  // never more energy than a perfect reflector
}
