// LDR-FLIP: identity, a hand-derived value for constant images, symmetry, monotonicity, and the
// pixels-per-degree dependence of the CSF.
#include <cmath>

#include <tbb/global_control.h>

#include "core/rng.h"
#include "metrics/image_metrics.h"
#include "metrics/flip.h"
#include "metrics/tonemap.h"
#include "test_support.h"

using namespace fovrt;
using fovrt::test::RandomImage;

namespace {

double Mean(const Plane<float>& p) {
    double s = 0;
    for (size_t i = 0; i < p.size(); ++i) s += p[i];
    return s / double(p.size());
}

// FLIP's colour redistribution (paper §4.1) for a HyAB distance, with cmax =
// HyAB(Hunt(Lab(green)), Hunt(Lab(blue)))^0.7 = 41.2761 (Lab green (87.736, −86.18, 83.18) and
// blue (32.298, 79.19, −107.86) after Hunt scaling, computed by hand from the CIE formulas).
double Redistribute(double hyab) {
    const double cmax = 41.2761, pc = 0.4 * cmax, p = std::pow(hyab, 0.7);
    return p < pc ? 0.95 / pc * p : 0.95 + (p - pc) / (cmax - pc) * 0.05;
}

}  // namespace

TEST_CASE("FLIP of identical images is 0", "[metrics][flip]") {
    Plane<vec3> img = RandomImage(48, 40, 1);
    Plane<float> map = FlipMap(img, img, 20.0f);
    for (size_t i = 0; i < map.size(); ++i) REQUIRE(map[i] == 0.0f);
}

TEST_CASE("FLIP of constant images is the colour term (hand-derived values)", "[metrics][flip]") {
    // Constant images have no features (kernels sum to 0 with replicated borders) and the CSF keeps
    // them constant, so FLIP = redistributed HyAB^0.7. For greys, a* = b* = 0 and
    // HyAB = |ΔL*| with L* = 116 Y^(1/3) − 16.
    SECTION("black vs white: HyAB = 100 -> 0.96738") {
        Plane<vec3> black(24, 24, vec3(0.0f)), white(24, 24, vec3(1.0f));
        double value = Mean(FlipMap(black, white, 30.0f));
        CHECK(value == Approx(0.96738).margin(2e-4));
        CHECK(value == Approx(Redistribute(100.0)).margin(2e-4));
    }
    SECTION("grey 0.2 vs 0.3 (linear)") {
        Plane<vec3> a(24, 24, vec3(0.2f)), b(24, 24, vec3(0.3f));
        const double dl = 116.0 * (std::cbrt(0.3) - std::cbrt(0.2));
        double value = Mean(FlipMap(a, b, 30.0f));
        CHECK(value == Approx(Redistribute(dl)).margin(5e-4));
        CHECK(value == Approx(0.28468).margin(5e-4));
        CHECK(FlipColorError(vec3(0.2f), vec3(0.3f)) == Approx(value).margin(5e-4));
    }
}

TEST_CASE("FLIP matches an independent direct-2D evaluation of the reference algorithm", "[metrics][flip]") {
    // Expected values from a plain-Python transcription of the published LDR-FLIP steps with
    // unfactored 2D kernels (CSF for all three opponent channels, edge and point detectors,
    // replicate borders) on this 12×10 chromatic pattern at 10 ppd, linear RGB in [0,1].
    const int w = 12, h = 10;
    Plane<vec3> ref(w, h), test(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            vec3 r(0.5 + 0.4 * std::sin(x * 0.9 + y * 0.3), 0.5 + 0.4 * std::cos(x * 0.5 - y * 0.7),
                   0.3 + 0.25 * std::sin(x * y * 0.2));
            vec3 d(0.15 * std::cos(x + 2.0 * y), -0.1 * std::sin(3.0 * x), 0.2 * ((x + y) % 3 - 1));
            ref(x, y) = r;
            test(x, y) = glm::clamp(r + d, vec3(0.0f), vec3(1.0f));
        }
    Plane<float> map = FlipMap(test, ref, 10.0f);
    CHECK(Mean(map) == Approx(0.4540690).margin(2e-4));
    CHECK(map(0, 0) == Approx(0.5651390).margin(5e-4));
    CHECK(map(5, 4) == Approx(0.4556755).margin(5e-4));
    CHECK(map(11, 9) == Approx(0.6218768).margin(5e-4));
    CHECK(map(3, 7) == Approx(0.3889889).margin(5e-4));
    CHECK(map(8, 2) == Approx(0.4369656).margin(5e-4));
}

TEST_CASE("FLIP is symmetric in test and reference", "[metrics][flip]") {
    Plane<vec3> a = RandomImage(40, 32, 5), b = RandomImage(40, 32, 6);
    Plane<float> ab = FlipMap(a, b, 25.0f), ba = FlipMap(b, a, 25.0f);
    for (size_t i = 0; i < ab.size(); ++i) REQUIRE(ab[i] == Approx(ba[i]).margin(1e-5));
}

TEST_CASE("FLIP on sRGB-encoded input equals FLIP on HDR through the tonemap", "[metrics][flip]") {
    Plane<vec3> a = RandomImage(40, 32, 7, 1.3f), b = RandomImage(40, 32, 8, 1.3f);
    Plane<float> hdr = FlipMap(a, b, 20.0f), ldr = FlipMapLdr(ToneMap(a), ToneMap(b), 20.0f);
    for (size_t i = 0; i < hdr.size(); ++i) REQUIRE(hdr[i] == Approx(ldr[i]).margin(1e-4));
}

TEST_CASE("FLIP grows with the error magnitude and stays in [0,1]", "[metrics][flip]") {
    // A smooth reference plus increasing noise.
    Plane<vec3> ref(64, 64), noise = RandomImage(64, 64, 9);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) ref(x, y) = vec3(0.2f + 0.5f * x / 63.0f, 0.3f, 0.6f - 0.4f * y / 63.0f);
    double previous = 0.0;
    for (float k : {0.02f, 0.05f, 0.1f, 0.2f, 0.4f}) {
        Plane<vec3> test = ref;
        for (size_t i = 0; i < test.size(); ++i) test[i] += k * (noise[i] - vec3(0.5f));
        Plane<float> map = FlipMap(test, ref, 20.0f);
        for (size_t i = 0; i < map.size(); ++i) REQUIRE((map[i] >= 0.0f && map[i] <= 1.0f));
        double value = Mean(map);
        CHECK(value > previous);
        previous = value;
    }
}

TEST_CASE("FLIP: a fine checkerboard looks closer to grey at more pixels per degree", "[metrics][flip]") {
    // The CSF blurs a one-pixel checkerboard more when each pixel subtends less angle.
    Plane<vec3> checker(64, 64), grey(64, 64, vec3(0.5f));
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) checker(x, y) = vec3(((x + y) & 1) ? 0.0f : 1.0f);
    double lowPpd = Mean(FlipMap(checker, grey, 8.0f));
    double highPpd = Mean(FlipMap(checker, grey, 67.0f));
    CHECK(highPpd < lowPpd);
    CHECK(lowPpd > 0.3);
}

TEST_CASE("FLIP uses the eye camera's pixels per degree", "[metrics][flip]") {
    // 1280 px over 90° -> 14.2 ppd (Quest-class would be ~20-25; a desktop ~67).
    EyeCamera eye(Pose{}, Fov::FromHorizontal(Radians(90.0f), 16.0f / 9.0f), 1280, 720);
    CHECK(eye.PixelsPerDegree() == Approx(1280.0f / 90.0f));
}

TEST_CASE("FLIP and SSIM maps are bit-identical for any thread count", "[metrics][flip]") {
    Plane<vec3> a = RandomImage(97, 61, 21, 1.2f), b = RandomImage(97, 61, 22, 1.2f);
    Plane<float> flipMany = FlipMap(a, b, 30.0f), ssimMany = SsimMap(a, b);
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    Plane<float> flipOne = FlipMap(a, b, 30.0f), ssimOne = SsimMap(a, b);
    CHECK(flipOne.vector() == flipMany.vector());
    CHECK(ssimOne.vector() == ssimMany.vector());
}
