// relMSE, SSIM, temporal error and masked means against closed forms and an independent
// brute-force SSIM.
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "metrics/image_metrics.h"
#include "metrics/tonemap.h"
#include "test_support.h"

using namespace fovrt;
using fovrt::test::RandomImage;

namespace {

// Direct 2D SSIM with the window cut at the border and renormalised (the documented definition),
// in double precision, written independently of the separable implementation.
double BruteSsimAt(const Plane<float>& x, const Plane<float>& y, int px, int py) {
    double wsum = 0, mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
    for (int dy = -5; dy <= 5; ++dy)
        for (int dx = -5; dx <= 5; ++dx) {
            int qx = px + dx, qy = py + dy;
            if (!x.InBounds(qx, qy)) continue;
            double w = std::exp(-(dx * dx + dy * dy) / (2 * 1.5 * 1.5));
            double a = x(qx, qy), b = y(qx, qy);
            wsum += w;
            mx += w * a;
            my += w * b;
            xx += w * a * a;
            yy += w * b * b;
            xy += w * a * b;
        }
    mx /= wsum, my /= wsum, xx /= wsum, yy /= wsum, xy /= wsum;
    double vx = xx - mx * mx, vy = yy - my * my, cxy = xy - mx * my;
    const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    return (2 * mx * my + c1) * (2 * cxy + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2));
}

}  // namespace

TEST_CASE("identical images: relMSE 0, SSIM 1, temporal 0", "[metrics]") {
    Plane<vec3> img = RandomImage(64, 64, 7, 2.0f);
    CHECK(RelMse(img, img) == 0.0);
    CHECK(Ssim(img, img) == Approx(1.0).margin(1e-6));
    CHECK(TemporalError(img, img) == 0.0);
}

TEST_CASE("relMSE of a constant offset matches the closed form per channel", "[metrics]") {
    const vec3 r(0.5f, 2.0f, 0.05f), d(0.1f, -0.3f, 0.2f);
    Plane<vec3> ref(64, 64, r), test(64, 64, r + d);
    double expected = 0;
    for (int c = 0; c < 3; ++c) expected += double(d[c]) * d[c] / (double(r[c]) * r[c] + 0.01);
    expected /= 3;
    CHECK(RelMse(test, ref) == Approx(expected).epsilon(1e-5));
    // ε is a parameter: ε = 1 changes the value as the formula says.
    double expectedEps1 = 0;
    for (int c = 0; c < 3; ++c) expectedEps1 += double(d[c]) * d[c] / (double(r[c]) * r[c] + 1.0);
    CHECK(RelMse(test, ref, nullptr, 1.0f) == Approx(expectedEps1 / 3).epsilon(1e-5));
    // relMSE is not symmetric: the reference is in the denominator.
    CHECK(RelMse(ref, test) != Approx(RelMse(test, ref)));
}

TEST_CASE("SSIM of two constant images is (2ab + C1) / (a² + b² + C1)", "[metrics]") {
    const float a = 0.05f, b = 0.5f;  // linear grey levels
    Plane<vec3> ref(32, 32, vec3(a)), test(32, 32, vec3(b));
    // Grey: Rec.709 weights sum to 1, so the luma is the sRGB-encoded grey level.
    const double la = SrgbEncode(a), lb = SrgbEncode(b), c1 = 1e-4;
    const double expected = (2 * la * lb + c1) / (la * la + lb * lb + c1);
    CHECK(Ssim(test, ref) == Approx(expected).epsilon(1e-6));
    CHECK(expected < 0.7);  // the case is not trivially near 1
}

TEST_CASE("SSIM worked example: two anticorrelated pixels", "[metrics]") {
    // 2×1 images x = [0, 1], y = [1, 0]. At pixel 0 the cut window holds offsets 0 and +1 with
    // Gaussian weights 1 and e^(−1/4.5); normalised w0, w1. Then μx = w1, μy = w0,
    // σx² = σy² = w0 w1, σxy = −w0 w1.
    Plane<float> x(2, 1), y(2, 1);
    x(0, 0) = 0, x(1, 0) = 1, y(0, 0) = 1, y(1, 0) = 0;
    const double g1 = std::exp(-1.0 / 4.5), w0 = 1 / (1 + g1), w1 = g1 / (1 + g1);
    const double c1 = 1e-4, c2 = 9e-4;
    const double expected =
        (2 * w0 * w1 + c1) * (-2 * w0 * w1 + c2) / ((w0 * w0 + w1 * w1 + c1) * (2 * w0 * w1 + c2));
    Plane<float> map = SsimMapOfLuma(x, y);
    CHECK(map(0, 0) == Approx(expected).epsilon(1e-4));
    CHECK(map(1, 0) == Approx(expected).epsilon(1e-4));  // mirror image of pixel 0
    CHECK(expected < -0.9);                              // strongly anticorrelated
}

TEST_CASE("SSIM map equals an independent brute-force 2D evaluation", "[metrics]") {
    Plane<vec3> ref = RandomImage(23, 17, 11, 1.5f), test = RandomImage(23, 17, 12, 1.5f);
    for (size_t i = 0; i < ref.size(); ++i) test[i] = 0.6f * ref[i] + 0.4f * test[i];  // correlated
    Plane<float> lx = DisplayLuma(test), ly = DisplayLuma(ref);
    Plane<float> map = SsimMap(test, ref);
    double sum = 0;
    for (int y = 0; y < 17; ++y)
        for (int x = 0; x < 23; ++x) {
            double expected = BruteSsimAt(lx, ly, x, y);
            CHECK(map(x, y) == Approx(expected).margin(2e-4));
            sum += expected;
        }
    CHECK(Ssim(test, ref) == Approx(sum / (23 * 17)).margin(1e-4));
}

TEST_CASE("SSIM decreases as noise grows", "[metrics]") {
    Plane<vec3> ref = RandomImage(64, 64, 3, 0.8f), noise = RandomImage(64, 64, 4);
    double previous = 1.0;
    for (float k : {0.05f, 0.1f, 0.2f, 0.4f}) {
        Plane<vec3> test = ref;
        for (size_t i = 0; i < test.size(); ++i) test[i] += k * (noise[i] - vec3(0.5f));
        double s = Ssim(test, ref);
        CHECK(s < previous);
        previous = s;
    }
}

TEST_CASE("temporal error is the mean absolute luminance change", "[metrics]") {
    Plane<vec3> a(16, 16, vec3(1.0f, 0.0f, 0.0f)), b(16, 16, vec3(0.0f, 1.0f, 0.0f));
    CHECK(TemporalError(a, b) == Approx(0.7152 - 0.2126).epsilon(1e-5));
    CHECK(TemporalError(b, a) == Approx(0.7152 - 0.2126).epsilon(1e-5));
}

TEST_CASE("masked means use only the masked pixels; empty mask gives NaN", "[metrics]") {
    Plane<float> map(4, 2);
    for (int i = 0; i < 8; ++i) map[size_t(i)] = float(i);
    Plane<uint8_t> mask(4, 2, 0);
    mask(1, 0) = mask(3, 1) = 1;  // values 1 and 7
    CHECK(MaskedMean(map, &mask) == Approx(4.0));
    CHECK(MaskedMean(map) == Approx(3.5));
    Plane<uint8_t> none(4, 2, 0);
    CHECK(std::isnan(MaskedMean(map, &none)));
}

TEST_CASE("tonemap is clamp + sRGB and round-trips on [0,1]", "[metrics]") {
    CHECK(ToneMap(vec3(0.0f)).x == 0.0f);
    CHECK(ToneMap(vec3(5.0f)).x == Approx(1.0f));
    CHECK(ToneMap(vec3(0.5f)).x == Approx(0.735357f).epsilon(1e-5));
    for (float v : {0.001f, 0.02f, 0.3f, 0.9f}) CHECK(SrgbDecode(SrgbEncode(v)) == Approx(v).epsilon(1e-5));
    CHECK(ToneMap(vec3(std::nanf(""))).x == 0.0f);
}
