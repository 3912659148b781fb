// spp models: disc radius in pixels, linear ramp, acuity formula, eccentricity as an angle.
#include <cmath>

#include "core/error.h"
#include "foveation/spp_model.h"
#include "gaze/gaze_source.h"
#include "test_support.h"

using namespace fovrt;

namespace {

EyeCamera SymmetricCamera(int w, int h, float hfovDeg = 90.0f) {
    return EyeCamera(Pose(), Fov::FromHorizontal(Radians(hfovDeg), float(w) / float(h)), w, h);
}

// Independent eccentricity of a pixel centre for a symmetric camera looking down -Z with the gaze
// straight ahead: the view ray's tangent-plane offset is (tx, ty), so e = atan(|(tx, ty)|).
double StraightAheadEccentricity(const EyeCamera& cam, int x, int y) {
    double tanX = std::tan(double(cam.fov().angleRight)), tanY = std::tan(double(cam.fov().angleUp));
    double tx = ((x + 0.5) / cam.width() * 2.0 - 1.0) * tanX;
    double ty = ((y + 0.5) / cam.height() * 2.0 - 1.0) * tanY;
    return std::atan(std::sqrt(tx * tx + ty * ty)) * 180.0 / M_PI;
}

}  // namespace

TEST_CASE("Disc: radius exact in pixels, scaled with the image width", "[foveation]") {
    FoveationParams p;  // thesis defaults: 200 px at 1280, 8 inside, 1 outside
    auto model = CreateSppModel(p);
    CHECK(model->Name() == "disc");

    EyeCamera cam = SymmetricCamera(1280, 720);
    // Gaze through the pixel corner (640, 360): pixel centres are at half-integer offsets.
    vec3 gaze = cam.EyeDirection(vec2(640.0f, 360.0f));
    Plane<uint16_t> spp;
    model->Generate(cam, gaze, 0, spp);
    REQUIRE(spp.width() == 1280);
    REQUIRE(spp.height() == 720);
    CHECK(spp(839, 360) == 8);   // centre at distance (199.5, 0.5): 199.5006
    CHECK(spp(840, 360) == 1);   // (200.5, 0.5): outside
    CHECK(spp(440, 360) == 8);   // (-199.5, 0.5)
    CHECK(spp(439, 360) == 1);
    CHECK(spp(640, 559) == 8);
    CHECK(spp(640, 560) == 1);
    // Diagonal: (141.5, 141.5) -> 200.11 outside; (140.5, 140.5) -> 198.7 inside.
    CHECK(spp(640 + 141, 360 + 141) == 1);
    CHECK(spp(640 + 140, 360 + 140) == 8);
    // The whole disc: count equals the closed-form count of pixel centres within 200 px.
    int inside = 0, expected = 0;
    for (int y = 0; y < 720; ++y)
        for (int x = 0; x < 1280; ++x) {
            double dx = x + 0.5 - 640.0, dy = y + 0.5 - 360.0;
            expected += dx * dx + dy * dy <= 200.0 * 200.0;
            inside += spp(x, y) == 8;
            REQUIRE((spp(x, y) == 8 || spp(x, y) == 1));
        }
    CHECK(inside == expected);

    // At 640x360 with the same FOV the radius is 100 px (same angle).
    EyeCamera half = SymmetricCamera(640, 360);
    model->Generate(half, half.EyeDirection(vec2(320.0f, 180.0f)), 0, spp);
    CHECK(spp(320 + 99, 180) == 8);
    CHECK(spp(320 + 100, 180) == 1);
}

TEST_CASE("Disc in degrees follows eccentricity", "[foveation]") {
    FoveationParams p;
    p.radiusDeg = 10.0f;
    auto model = CreateSppModel(p);
    EyeCamera cam = SymmetricCamera(64, 64);
    Plane<uint16_t> spp;
    model->Generate(cam, vec3(0, 0, -1), 0, spp);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            REQUIRE(spp(x, y) == (StraightAheadEccentricity(cam, x, y) <= 10.0 ? 8 : 1));
}

TEST_CASE("Linear falloff matches the ramp at given eccentricities", "[foveation]") {
    FoveationParams p;
    p.model = "linear";
    p.sppMax = 16;
    p.sppMin = 2;
    p.fovealDeg = 5.0f;
    p.peripheralDeg = 30.0f;
    auto model = CreateSppModel(p);
    EyeCamera cam = SymmetricCamera(128, 72, 100.0f);
    Plane<float> density;
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, density);
    Plane<uint16_t> spp;
    model->Generate(cam, vec3(0, 0, -1), 0, spp);
    auto ramp = [](double e) { return e <= 5 ? 16.0 : e >= 30 ? 2.0 : 16.0 + (e - 5.0) / 25.0 * (2.0 - 16.0); };
    int inRamp = 0;
    for (int y = 0; y < 72; ++y)
        for (int x = 0; x < 128; ++x) {
            double e = StraightAheadEccentricity(cam, x, y);
            REQUIRE(density(x, y) == Approx(ramp(e)).margin(1e-3));
            REQUIRE(spp(x, y) == std::lround(density(x, y)));
            inRamp += e > 5 && e < 30;
        }
    CHECK(inRamp > 100);  // the test really sampled the ramp
    // Spot values: e = 17.5 deg is half-way -> 9.
    CHECK(ramp(17.5) == Approx(9.0));
}

TEST_CASE("Acuity model: formula and monotone in eccentricity", "[foveation]") {
    FoveationParams p;
    p.model = "acuity";
    p.sppMax = 16;
    p.sppMin = 1;
    p.omega0Deg = 1.0f / 48.0f;
    p.marSlope = 0.022f;
    auto model = CreateSppModel(p);
    EyeCamera cam = SymmetricCamera(200, 50, 8.0f);  // narrow FOV: eccentricities 0..4 deg
    Plane<float> density;
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, density);
    float previous = 1e9f;
    for (int x = 100; x < 200; ++x) {  // centre row, moving outward
        double e = StraightAheadEccentricity(cam, x, 25);
        double w0 = 1.0 / 48.0, rho = std::pow(w0 / (w0 + 0.022 * e), 2.0);
        REQUIRE(density(x, 25) == Approx(std::clamp(16.0 * rho, 1.0, 16.0)).epsilon(1e-4));
        REQUIRE(density(x, 25) <= previous);
        previous = density(x, 25);
    }
    CHECK(density(100, 25) > 15.0f);  // near the gaze: close to spp_max
    CHECK(density(199, 25) == 1.0f);  // far out: clamped at spp_min
}

TEST_CASE("Eccentricity is the angle between view ray and gaze (asymmetric FOV)", "[foveation]") {
    Fov fov{Radians(-52.0f), Radians(38.0f), Radians(41.0f), Radians(-29.0f)};
    EyeCamera cam(Pose(), fov, 96, 80);
    vec3 gaze = GazeDirectionFromAngles(12.0f, -7.0f);
    // Directions at a known angle from the gaze: rotate it about axes perpendicular to it.
    vec3 perpA = glm::normalize(glm::cross(gaze, vec3(0, 1, 0)));
    vec3 perpB = glm::cross(gaze, perpA);
    for (float theta : {0.5f, 5.0f, 17.0f, 25.0f}) {
        for (vec3 axis : {perpA, perpB, glm::normalize(perpA + perpB), -perpA}) {
            vec3 d = glm::angleAxis(Radians(theta), axis) * gaze;
            vec2 pixel = cam.PixelOfEyeDirection(d);
            CHECK(EccentricityDegrees(cam, pixel, gaze) == Approx(theta).margin(2e-3));
        }
    }
    // At equal pixel distances left and right of the gaze pixel, an asymmetric frustum gives
    // different angles: eccentricity is not a pixel distance.
    vec2 g = cam.PixelOfEyeDirection(gaze);
    float left = EccentricityDegrees(cam, g - vec2(30, 0), gaze);
    float right = EccentricityDegrees(cam, g + vec2(30, 0), gaze);
    CHECK(std::abs(left - right) > 0.5f);
}

TEST_CASE("Uniform model and parameter errors", "[foveation]") {
    FoveationParams p;
    p.model = "uniform";
    p.uniformSpp = 3;
    Plane<uint16_t> spp;
    CreateSppModel(p)->Generate(SymmetricCamera(64, 64), vec3(0.3f, 0, -1), 7, spp);
    for (size_t i = 0; i < spp.size(); ++i) REQUIRE(spp[i] == 3);

    FoveationParams bad;
    bad.model = "gaussian";
    CHECK_THROWS_WITH(CreateSppModel(bad), Catch::Contains("foveation.model") && Catch::Contains("gaussian"));
    bad = FoveationParams();
    bad.sppInside = 65;
    CHECK_THROWS_WITH(CreateSppModel(bad), Catch::Contains("foveation.spp_inside"));
    bad = FoveationParams();
    bad.peripheralDeg = 2.0f;
    CHECK_THROWS_WITH(CreateSppModel(bad), Catch::Contains("foveation.peripheral_deg"));
    bad = FoveationParams();
    bad.rayBudget = -5;
    CHECK_THROWS_AS(CreateSppModel(bad), Error);
}
