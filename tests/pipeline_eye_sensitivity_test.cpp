// The perceptual spp model with the metric's own contrast sensitivity (FovVideoVDP's CSF with its
// cortical magnification): the map falls monotonically with eccentricity on a headset-like eye,
// follows the CSF's ratio S(e) / S(0), and under a ray budget meets it.
#include <cmath>

#include "metrics/vdp_csf.h"
#include "metrics/vdp_params.h"
#include "pipeline/eye_sensitivity.h"
#include "test_support.h"

using namespace fovrt;

TEST_CASE("The metric's CSF is what the perceptual model reads", "[foveation]") {
    const ContrastSensitivity s = MetricContrastSensitivity();
    const VdpParams params;
    for (double e : {0.0, 5.0, 30.0})
        CHECK(s(3.2, 50.0, e) == VdpCsfModel(3.2, 0.0, 50.0, e, params.csfSigma, params.kCm));
    // Cortical magnification: the same grating is harder to see off-axis.
    CHECK(s(3.2, 50.0, 20.0) < 0.5 * s(3.2, 50.0, 0.0));
}

TEST_CASE("Perceptual with the metric's CSF: falls monotonically with eccentricity, meets a budget",
          "[foveation]") {
    // 90° wide: 7.1 ppd, so the noise (half of Nyquist, 1.8 cpd) lies above the CSF's peak (about
    // 1 cpd) and S falls from the gaze on (below the peak the model holds it flat, see models.cpp).
    const int w = 640, h = 180;
    const EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(90.0f), float(w) / h), w, h);
    FoveationParams p;
    p.model = "perceptual";
    p.sppMin = kMinSpp;
    auto model = CreateSppModel(p, MetricContrastSensitivity());
    Plane<float> density;
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, density);
    const double rho = 0.5 * 0.5 * cam.PixelsPerDegree();
    const ContrastSensitivity s = MetricContrastSensitivity();
    float previous = 1e9f;
    for (int x = w / 2; x < w; ++x) {  // the centre row, outward
        REQUIRE(density(x, h / 2) <= previous);
        previous = density(x, h / 2);
        const vec3 ray = cam.EyeDirection(vec2(x + 0.5f, h / 2 + 0.5f));
        const double e = Degrees(std::acos(double(-ray.z)));
        const double expected = std::max(8.0 * s(rho, 50.0, e) / s(rho, 50.0, 0.0), double(kMinSpp));
        REQUIRE(density(x, h / 2) == Approx(expected).epsilon(1e-2));
    }
    CHECK(density(w / 2, h / 2) > 7.9f);
    CHECK(previous < 2.0f);  // 45° out

    p.sppFloor = kMinSpp;
    p.rayBudget = int64_t(w) * h / 2;  // 0.5 spp
    model = CreateSppModel(p, MetricContrastSensitivity());
    int64_t total = 0;
    Plane<uint16_t> spp;
    for (uint32_t t = 0; t < 16; ++t) {
        model->Generate(cam, vec3(0, 0, -1), t, spp);
        for (size_t i = 0; i < spp.size(); ++i) total += spp[i];
    }
    CHECK(std::abs(double(total) - 16.0 * double(p.rayBudget)) <= 0.01 * 16.0 * double(p.rayBudget));
}
