// The perceptual spp model with a made-up contrast sensitivity, so each term has a closed form:
// spp_max · S(e) / S(0) at the frequency and luminance the keys give, non-increasing in e, and
// under a ray budget n ∝ S with the budget met.
#include <cmath>
#include <vector>

#include "core/error.h"
#include "foveation/spp_model.h"
#include "test_support.h"

using namespace fovrt;

namespace {

// Independent eccentricity of a pixel centre, gaze straight ahead, symmetric camera.
double StraightAheadEccentricity(const EyeCamera& cam, int x, int y) {
    double tanX = std::tan(double(cam.fov().angleRight)), tanY = std::tan(double(cam.fov().angleUp));
    double tx = ((x + 0.5) / cam.width() * 2.0 - 1.0) * tanX;
    double ty = ((y + 0.5) / cam.height() * 2.0 - 1.0) * tanY;
    return std::atan(std::sqrt(tx * tx + ty * ty)) * 180.0 / M_PI;
}

// S = 1 / (1 + e / 5): falls smoothly, S(0) = 1.
double Hyperbolic(double, double, double e) { return 1.0 / (1.0 + e / 5.0); }

FoveationParams Perceptual() {
    FoveationParams p;
    p.model = "perceptual";
    p.sppMax = 16;
    p.sppMin = kMinSpp;
    return p;
}

}  // namespace

TEST_CASE("Perceptual: spp_max S(e)/S(0) at each pixel's eccentricity", "[foveation]") {
    const EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(100.0f), 1.0f), 96, 96);
    auto model = CreateSppModel(Perceptual(), Hyperbolic);
    CHECK(model->Name() == "perceptual");
    Plane<float> density;
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, density);
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x) {
            const double e = StraightAheadEccentricity(cam, x, y);
            // The table over √e interpolates linearly: within 0.5 % of the closed form.
            REQUIRE(density(x, y) == Approx(std::max(16.0 * Hyperbolic(0, 0, e), double(kMinSpp))).epsilon(5e-3));
        }
}

TEST_CASE("Perceptual: the CSF is read at noise_frequency x Nyquist and adapt_luminance", "[foveation]") {
    const EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(80.0f), 1.0f), 64, 64);  // 0.8 ppd
    FoveationParams p = Perceptual();
    p.noiseFrequency = 0.25f;
    p.adaptLuminance = 12.5f;
    std::vector<double> rhos, luminances;
    auto spy = [&](double rho, double luminance, double e) {
        rhos.push_back(rho), luminances.push_back(luminance);
        return Hyperbolic(rho, luminance, e);
    };
    Plane<float> density;
    CreateSppModel(p, spy)->GenerateDensity(cam, vec3(0, 0, -1), 0, density);
    REQUIRE(!rhos.empty());
    for (double rho : rhos) CHECK(rho == Approx(0.25 * 0.5 * 64.0 / 80.0));
    for (double luminance : luminances) CHECK(luminance == 12.5);
}

TEST_CASE("Perceptual: never more samples off-axis than at the gaze (sensitivity held non-increasing)",
          "[foveation]") {
    // A CSF below its peak rises off-axis (S(ρ / M(e))): the map must not.
    auto rising = [](double, double, double e) { return e < 10.0 ? 1.0 + e / 10.0 : 2.0 / (1.0 + (e - 10.0)); };
    const EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(100.0f), 2.0f), 128, 64);
    FoveationParams p = Perceptual();
    p.sppMax = 8;
    Plane<float> density;
    CreateSppModel(p, rising)->GenerateDensity(cam, vec3(0, 0, -1), 0, density);
    float previous = 1e9f;
    for (int x = 64; x < 128; ++x) {  // the centre row, outward
        REQUIRE(density(x, 32) <= previous);
        previous = density(x, 32);
    }
    CHECK(density(64, 32) == Approx(8.0f).epsilon(1e-2));
    CHECK(previous < 1.0f);
}

TEST_CASE("Perceptual under a ray budget: n proportional to S, budget met", "[foveation]") {
    const int w = 96, h = 64;
    const EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(100.0f), float(w) / h), w, h);
    FoveationParams p = Perceptual();
    p.sppFloor = kMinSpp;
    for (double perPixel : {0.5, 2.0}) {
        p.rayBudget = int64_t(perPixel * w * h);
        INFO("budget " << perPixel << " spp");
        auto model = CreateSppModel(p, Hyperbolic);
        CHECK(model->Name() == "budget(perceptual)");
        Plane<float> density;
        model->GenerateDensity(cam, vec3(0, 0, -1), 0, density);
        // n_i = s · S_i wherever no bound binds (Lagrange: minimising Σ S²/n at Σ n = B).
        double sum = 0.0, ratio = -1.0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                sum += density(x, y);
                const double s = Hyperbolic(0, 0, StraightAheadEccentricity(cam, x, y));
                if (density(x, y) > kMinSpp && density(x, y) < float(kMaxSpp)) {
                    if (ratio < 0) ratio = density(x, y) / s;
                    REQUIRE(density(x, y) / s == Approx(ratio).epsilon(1e-2));
                }
            }
        CHECK(sum == Approx(double(p.rayBudget)).margin(0.1));
        // The integer maps: over 16 frames the total is the budget's within 1 %.
        int64_t total = 0;
        Plane<uint16_t> spp;
        for (uint32_t t = 0; t < 16; ++t) {
            model->Generate(cam, vec3(0, 0, -1), t, spp);
            for (size_t i = 0; i < spp.size(); ++i) total += spp[i];
        }
        CHECK(std::abs(double(total) - 16.0 * double(p.rayBudget)) <= 0.01 * 16.0 * double(p.rayBudget));
    }
}

TEST_CASE("Perceptual without a contrast sensitivity names the key", "[foveation]") {
    CHECK_THROWS_WITH(CreateSppModel(Perceptual()), Catch::Contains("foveation.model") &&
                                                        Catch::Contains("perceptual"));
    FoveationParams bad = Perceptual();
    bad.noiseFrequency = 0.0f;
    CHECK_THROWS_WITH(CreateSppModel(bad, Hyperbolic), Catch::Contains("foveation.noise_frequency"));
}

// ---- The content term: fewer samples where the content's texture masks noise ----

namespace {

// Luminance L0 (1 + m cos(2π x / period)): a vertical grating of Weber contrast m.
Plane<float> Grating(int w, int h, double period, double m, float l0 = 1.0f) {
    Plane<float> l(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) l(x, y) = l0 * float(1.0 + m * std::cos(2.0 * M_PI * x / period));
    return l;
}

// Made-up masking constants: k·gain·S(0) = 100 with Hyperbolic's S(0) = 1, q = 2.
constexpr ContrastMasking kMasking{1000.0, 0.1, 2.0};

}  // namespace

TEST_CASE("LocalBandContrast: zero on flat content, scale-free, a grating's band energy in closed form",
          "[foveation]") {
    const Plane<float> flatContrast = LocalBandContrast(Plane<float>(48, 32, 3.0f), 0.25);
    for (float c : flatContrast.vector()) REQUIRE(c == 0.0f);

    // The band at 1/4 cycle per pixel is level 1: fine = B1 L, coarse = B2 fine, the binomial
    // [1 4 6 4 1]/16 with taps s apart passing cos⁴(π f s) of frequency f. A grating of period 6
    // and contrast m has band contrast m·cos⁴(π/6)·(1 − cos⁴(π/3)) cos(…) to first order in m; its
    // square, averaged over a period, is half that amplitude squared.
    const double m = 0.1, gain = std::pow(std::cos(M_PI / 6), 4) * (1.0 - std::pow(std::cos(M_PI / 3), 4));
    const Plane<float> c = LocalBandContrast(Grating(96, 24, 6.0, m), 0.25);
    double energy = 0.0;
    int n = 0;
    for (int x = 24; x < 72; ++x, ++n) energy += double(c(x, 12)) * c(x, 12);  // 8 periods, away from edges
    CHECK(energy / n == Approx(m * m * gain * gain / 2.0).epsilon(0.01));
    // Weber contrast: the content's scale does not matter.
    const Plane<float> brighter = LocalBandContrast(Grating(96, 24, 6.0, m, 7.0f), 0.25);
    for (size_t i = 0; i < c.size(); ++i) REQUIRE(brighter[i] == Approx(c[i]).epsilon(1e-5));
}

TEST_CASE("Perceptual content term: n scaled by 1/sqrt(1 + (k S C)^q), flat content unchanged", "[foveation]") {
    const int w = 96, h = 64;
    const EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(100.0f), float(w) / h), w, h);
    FoveationParams p = Perceptual();
    Plane<float> plain;
    CreateSppModel(p, Hyperbolic)->GenerateDensity(cam, vec3(0, 0, -1), 0, plain);
    p.contentMasking = true;
    auto model = CreateSppModel(p, Hyperbolic, kMasking);

    // Flat content (and no content, as after a cut) masks nothing: the map without the term.
    Plane<float> density;
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, density);
    for (size_t i = 0; i < density.size(); ++i) REQUIRE(density[i] == plain[i]);
    const Plane<float> flat(w, h, 0.4f);
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, density, {&flat});
    for (size_t i = 0; i < density.size(); ++i) REQUIRE(density[i] == plain[i]);

    // A grating on the right half: there the density is the flat map's times the masking factor,
    // with S(e)/S(0) read from the flat map (16 S/S(0) wherever above spp_min).
    Plane<float> content = Grating(w, h, 6.0, 0.2);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w / 2; ++x) content(x, y) = 1.0f;
    const Plane<float> contrast = LocalBandContrast(content, 0.25);
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, density, {&content});
    int masked = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double relative = plain(x, y) / 16.0;
            if (plain(x, y) <= kMinSpp) continue;
            const double factor = 1.0 / std::sqrt(1.0 + std::pow(100.0 * relative * contrast(x, y), 2.0));
            REQUIRE(density(x, y) == Approx(std::max(16.0 * relative * factor, double(kMinSpp))).epsilon(1e-4));
            if (x >= w / 2 + 8) {
                REQUIRE(density(x, y) < 0.95f * plain(x, y));  // the texture hides noise: fewer samples
                ++masked;
            }
        }
    CHECK(masked > 500);
}

TEST_CASE("Perceptual content term under a ray budget: the budget met, the rays moved off the texture",
          "[foveation]") {
    const int w = 96, h = 64;
    const EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(100.0f), float(w) / h), w, h);
    FoveationParams p = Perceptual();
    p.contentMasking = true;
    p.sppFloor = kMinSpp;
    p.rayBudget = int64_t(w) * h;  // 1 spp
    auto model = CreateSppModel(p, Hyperbolic, kMasking);
    Plane<float> content = Grating(w, h, 6.0, 0.2);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w / 2; ++x) content(x, y) = 1.0f;
    Plane<float> flat, textured;
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, flat);
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, textured, {&content});
    double sumFlat = 0.0, sumTextured = 0.0, left = 0.0, right = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            sumFlat += flat(x, y), sumTextured += textured(x, y);
            (x < w / 2 ? left : right) += textured(x, y);
        }
    CHECK(sumFlat == Approx(double(p.rayBudget)).margin(0.1));
    CHECK(sumTextured == Approx(double(p.rayBudget)).margin(0.1));
    CHECK(right < 0.8 * left);  // mirror-symmetric eccentricities: only the content differs
}

TEST_CASE("Perceptual content term: refusals name the key", "[foveation]") {
    FoveationParams p = Perceptual();
    p.contentMasking = true;
    CHECK_THROWS_WITH(CreateSppModel(p, Hyperbolic), Catch::Contains("foveation.content_masking"));
    FoveationParams linear = p;
    linear.model = "linear";
    CHECK_THROWS_WITH(CreateSppModel(linear), Catch::Contains("foveation.content_masking") &&
                                                  Catch::Contains("perceptual model only"));
    const EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(100.0f), 1.0f), 32, 32);
    const Plane<float> wrong(16, 32, 1.0f);
    Plane<float> density;
    CHECK_THROWS_WITH(CreateSppModel(p, Hyperbolic, kMasking)->GenerateDensity(cam, vec3(0, 0, -1), 0, density, {&wrong}),
                      Catch::Contains("foveation.content_masking") && Catch::Contains("16x32"));
}

TEST_CASE("Perceptual pooling = metric: n proportional to S^(2pb/(pb+2)), the masking to the power 2b/(pb+2)",
          "[foveation]") {
    // Made-up exponents p = 3, β = 2: a = pβ = 6, so n ∝ S^1.5 and the masking factor M^-0.5.
    const ContrastMasking metric{1000.0, 0.1, 2.0, 3.0, 2.0};
    const int w = 96, h = 64;
    const EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(100.0f), float(w) / h), w, h);
    FoveationParams p = Perceptual();
    p.pooling = "metric";
    Plane<float> density;
    CreateSppModel(p, Hyperbolic, metric)->GenerateDensity(cam, vec3(0, 0, -1), 0, density);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double s = Hyperbolic(0, 0, StraightAheadEccentricity(cam, x, y));
            REQUIRE(density(x, y) == Approx(std::max(16.0 * std::pow(s, 1.5), double(kMinSpp))).epsilon(1e-2));
        }
    // The metric's own p = 2.4 and β = 1.52 give 1.29: steeper than the energy's n ∝ S.
    const double a = 2.4 * 1.52;
    CHECK(2.0 * a / (a + 2.0) == Approx(1.2907).epsilon(1e-3));

    // With content, the factor is M^(-2β/(a+2)) = M^(-1/2) here too; p = 2, β = 2 gives M^(-2/3).
    p.contentMasking = true;
    const ContrastMasking steep{1000.0, 0.1, 2.0, 2.0, 2.0};
    Plane<float> content = Grating(w, h, 6.0, 0.2);
    const Plane<float> contrast = LocalBandContrast(content, 0.25);
    Plane<float> flat, masked;
    auto model = CreateSppModel(p, Hyperbolic, steep);
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, flat);
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, masked, {&content});
    int checked = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // a = 4: n ∝ S^(4/3), so S(e)/S(0) = (flat / 16)^(3/4) wherever above spp_min.
            if (flat(x, y) <= kMinSpp) continue;
            const double relative = std::pow(flat(x, y) / 16.0, 0.75);
            const double m = 1.0 + std::pow(100.0 * relative * contrast(x, y), 2.0);
            REQUIRE(masked(x, y) == Approx(std::max(flat(x, y) * std::pow(m, -2.0 / 3.0), double(kMinSpp))).epsilon(1e-3));
            ++checked;
        }
    CHECK(checked > 1000);
}

TEST_CASE("Perceptual pooling = metric: refusals name the key", "[foveation]") {
    FoveationParams p = Perceptual();
    p.pooling = "metric";
    CHECK_THROWS_WITH(CreateSppModel(p, Hyperbolic), Catch::Contains("foveation.pooling"));
    p.model = "acuity";
    CHECK_THROWS_WITH(CreateSppModel(p), Catch::Contains("foveation.pooling") && Catch::Contains("perceptual model only"));
    p.model = "perceptual";
    p.pooling = "l2";
    CHECK_THROWS_WITH(CreateSppModel(p, Hyperbolic, kMasking), Catch::Contains("foveation.pooling"));
}
