// Region masks against geometry: disc area, band boundaries, off-axis cameras.
#include <cmath>

#include "core/error.h"
#include "metrics/error_maps.h"
#include "metrics/regions.h"
#include "test_support.h"

using namespace fovrt;

namespace {

Fov MakeFov(float left, float right, float up, float down) {
    Fov f;
    f.angleLeft = Radians(left);
    f.angleRight = Radians(right);
    f.angleUp = Radians(up);
    f.angleDown = Radians(down);
    return f;
}

// Independent eye-space direction of a pixel centre from the FOV tangents.
vec3 DirectionOf(const Fov& f, int w, int h, int x, int y) {
    double u = (x + 0.5) / w, v = (y + 0.5) / h;
    double tx = std::tan(f.angleLeft) + u * (std::tan(f.angleRight) - std::tan(f.angleLeft));
    double ty = std::tan(f.angleUp) + v * (std::tan(f.angleDown) - std::tan(f.angleUp));
    return glm::normalize(vec3(float(tx), float(ty), -1.0f));
}

double AngleDeg(const vec3& a, const vec3& b) {
    double c = std::clamp(double(glm::dot(glm::normalize(a), glm::normalize(b))), -1.0, 1.0);
    return std::acos(c) * 180.0 / 3.14159265358979;
}

}  // namespace

TEST_CASE("pixel fovea is a gaze-centred disc of area ≈ πr²", "[metrics][regions]") {
    EyeCamera eye(Pose{}, MakeFov(-45, 45, 45, -45), 128, 128);
    RegionSet set = RegionSet::Build(eye, vec3(0, 0, -1), FoveaRadius::Pixels(20.0f));
    CHECK(set.gazePixel().x == Approx(64.0f));
    CHECK(set.gazePixel().y == Approx(64.0f));
    const Region* fovea = set.Find("fovea");
    const Region* periphery = set.Find("periphery");
    REQUIRE(fovea);
    REQUIRE(periphery);
    CHECK(double(fovea->pixelCount) == Approx(kPi * 400.0).epsilon(0.02));
    CHECK(fovea->pixelCount + periphery->pixelCount == 128u * 128u);
    CHECK(set.Find("whole")->pixelCount == 128u * 128u);
    for (size_t i = 0; i < fovea->mask.size(); ++i) REQUIRE(fovea->mask[i] + periphery->mask[i] == 1);
    CHECK(fovea->mask(64, 64) == 1);
    CHECK(fovea->mask(64 + 25, 64) == 0);
    CHECK(fovea->mask(64 + 18, 64) == 1);
}

TEST_CASE("an off-centre gaze moves the disc to the gaze pixel", "[metrics][regions]") {
    EyeCamera eye(Pose{}, MakeFov(-40, 50, 35, -30), 160, 120);
    const vec2 target(120.25f, 30.75f);
    const vec3 gaze = eye.EyeDirection(target);
    RegionSet set = RegionSet::Build(eye, gaze, FoveaRadius::Pixels(10.0f));
    CHECK(set.gazePixel().x == Approx(target.x).margin(1e-3));
    CHECK(set.gazePixel().y == Approx(target.y).margin(1e-3));
    const Region* fovea = set.Find("fovea");
    CHECK(double(fovea->pixelCount) == Approx(kPi * 100.0).epsilon(0.04));
    CHECK(fovea->mask(120, 30) == 1);
    CHECK(fovea->mask(60, 60) == 0);
}

TEST_CASE("on-axis 0–5° band covers a disc of radius tan 5° in tangent space", "[metrics][regions]") {
    const int w = 256, h = 256;
    EyeCamera eye(Pose{}, MakeFov(-40, 40, 40, -40), w, h);
    RegionSet set = RegionSet::Build(eye, vec3(0, 0, -1));
    const double pixelArea = (2 * std::tan(Radians(40.0f)) / w) * (2 * std::tan(Radians(40.0f)) / h);
    const double t5 = std::tan(Radians(5.0f)), t10 = std::tan(Radians(10.0f));
    CHECK(double(set.Find("ecc0-5")->pixelCount) == Approx(kPi * t5 * t5 / pixelArea).epsilon(0.03));
    CHECK(double(set.Find("ecc5-10")->pixelCount) == Approx(kPi * (t10 * t10 - t5 * t5) / pixelArea).epsilon(0.03));
    size_t total = 0;
    for (const char* name : {"ecc0-5", "ecc5-10", "ecc10-20", "ecc20+"}) total += set.Find(name)->pixelCount;
    CHECK(total == size_t(w) * h);  // the bands partition the image
}

TEST_CASE("band boundaries sit at the right angles in an off-axis camera", "[metrics][regions]") {
    const int w = 200, h = 150;
    const Fov fov = MakeFov(-30, 55, 40, -20);  // asymmetric, like a VR eye
    EyeCamera eye(Pose{}, fov, w, h);
    const vec3 gaze = glm::normalize(vec3(0.3f, -0.1f, -1.0f));
    RegionSet set = RegionSet::Build(eye, gaze, FoveaRadius::Degrees(7.5f));
    const float bounds[] = {0, 5, 10, 20, 1e9f};
    const char* names[] = {"ecc0-5", "ecc5-10", "ecc10-20", "ecc20+"};
    const double pixelDeg = 85.0 / w;  // about one pixel's angle near the axis
    for (int b = 0; b < 4; ++b) {
        const Region* r = set.Find(names[b]);
        REQUIRE(r);
        REQUIRE(r->pixelCount > 0);
        double lo = 1e9, hi = -1;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                double e = AngleDeg(DirectionOf(fov, w, h, x, y), gaze);
                if (r->mask(x, y)) {
                    lo = std::min(lo, e);
                    hi = std::max(hi, e);
                    REQUIRE(e >= bounds[b] - 1e-3);
                    REQUIRE(e < bounds[b + 1] + 1e-3);
                }
            }
        if (b > 0) CHECK(lo < bounds[b] + pixelDeg);       // band starts at its boundary
        if (b < 3) CHECK(hi > bounds[b + 1] - pixelDeg);   // and reaches the next one
    }
    // Degree fovea: exactly the pixels under 7.5°.
    const Region* fovea = set.Find("fovea");
    for (int y = 0; y < h; y += 3)
        for (int x = 0; x < w; x += 3) {
            double e = AngleDeg(DirectionOf(fov, w, h, x, y), gaze);
            if (std::abs(e - 7.5) > 1e-3) REQUIRE(fovea->mask(x, y) == (e < 7.5 ? 1 : 0));
        }
}

TEST_CASE("a backward gaze has an empty pixel fovea; bad inputs are errors", "[metrics][regions]") {
    EyeCamera eye(Pose{}, MakeFov(-45, 45, 45, -45), 32, 32);
    RegionSet set = RegionSet::Build(eye, vec3(0, 0, 1), FoveaRadius::Pixels(10.0f));
    CHECK(set.Find("fovea")->pixelCount == 0u);
    CHECK_THROWS_AS(RegionSet::Build(eye, vec3(0.0f), {}), Error);
    CHECK_THROWS_AS(RegionSet::Build(eye, vec3(0, 0, -1), FoveaRadius::Pixels(-1.0f)), Error);
}

TEST_CASE("MeanOverRegions reports every metric for every non-empty region", "[metrics][regions]") {
    EyeCamera eye(Pose{}, MakeFov(-45, 45, 45, -45), 32, 32);
    RegionSet set = RegionSet::Build(eye, vec3(0, 0, -1), FoveaRadius::Pixels(8.0f));
    Plane<vec3> ref(32, 32, vec3(0.5f)), test(32, 32, vec3(0.6f));
    ErrorMaps maps = ComputeErrorMaps(test, ref, {eye.PixelsPerDegree(), 0.01f}, &ref);
    auto values = MeanOverRegions(maps, set);
    // 7 regions (the 20°+ band of a 90° view is non-empty) × 4 metrics.
    CHECK(values.size() == 7u * 4u);
    for (const RegionValue& v : values)
        if (v.metric == "relmse") CHECK(v.value == Approx(0.01 / 0.26).epsilon(1e-4));
}
