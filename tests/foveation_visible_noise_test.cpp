// The perceptual model's noise term: VisibleNoiseEstimator against noise of known contrast, and the
// density n ∝ S(ρ, L, e) · σ/L with made-up sensitivities whose answers are closed forms.
#include <cmath>
#include <random>

#include "core/error.h"
#include "foveation/spp_model.h"
#include "foveation/visible_noise.h"
#include "test_support.h"

using namespace fovrt;

namespace {

// A frame of mean luminance `signal(x, y)` whose pixel i, the mean of nᵢ samples of standard
// deviation `sigma(x, y)`, is Gaussian with σ/√nᵢ; nᵢ cycles through 1, 2, 4 and, where `holes`,
// 0 (such a pixel holds `hole`, which must not be read).
struct NoisyFrame {
    Plane<float> display;
    Plane<uint16_t> count;
};
template <typename Signal, typename Sigma>
NoisyFrame MakeFrame(int w, int h, Signal signal, Sigma sigma, uint32_t seed, bool holes = false,
                     float hole = 1e9f) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> gauss;
    NoisyFrame f{Plane<float>(w, h), Plane<uint16_t>(w, h)};
    static constexpr uint16_t kCounts[4] = {1, 2, 4, 0};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const uint16_t n = kCounts[(x + 2 * y) % (holes ? 4 : 3)];
            f.count(x, y) = n;
            f.display(x, y) = n == 0 ? hole : float(signal(x, y) + sigma(x, y) / std::sqrt(double(n)) * gauss(rng));
        }
    return f;
}

FoveationParams Perceptual() {
    FoveationParams p;
    p.model = "perceptual";
    p.sppMax = 16;
    p.sppMin = kMinSpp;
    p.noiseVisibility = true;
    return p;
}

// S independent of eccentricity and frequency, ∝ √L (de Vries–Rose): the luminance alone moves it.
double RootLuminance(double, double luminance, double) { return std::sqrt(luminance); }

// A VisibleNoise with two halves: left (L, r) = (lumLeft, rLeft), right (lumRight, rRight), 8-px tiles.
VisibleNoise Halves(int w, int h, float lumLeft, float rLeft, float lumRight, float rRight) {
    VisibleNoise n;
    n.tileSize = 8;
    n.imageWidth = w, n.imageHeight = h;
    n.luminance.Resize(w / 8, h / 8);
    n.contrast.Resize(w / 8, h / 8);
    for (int y = 0; y < h / 8; ++y)
        for (int x = 0; x < w / 8; ++x) {
            const bool left = x < w / 16;
            n.luminance(x, y) = left ? lumLeft : lumRight;
            n.contrast(x, y) = left ? rLeft : rRight;
        }
    n.meanContrast = 0.5f * (rLeft + rRight);
    return n;
}

}  // namespace

TEST_CASE("VisibleNoise: one sample's noise contrast and the luminance, from pixels of 1, 2 and 4 samples",
          "[foveation]") {
    // Flat signal 40 cd/m² with σ = 6 per sample: r = 0.15 in every tile, over several frames pooled.
    VisibleNoiseEstimator estimator(16);
    for (uint32_t frame = 0; frame < 4; ++frame) {
        const NoisyFrame f = MakeFrame(64, 48, [](int, int) { return 40.0; }, [](int, int) { return 6.0; }, frame);
        estimator.Add(f.display, f.count);
    }
    const VisibleNoise& noise = estimator.Noise();
    REQUIRE(noise.Valid());
    REQUIRE(noise.contrast.width() == 4);
    REQUIRE(noise.contrast.height() == 3);
    for (size_t i = 0; i < noise.contrast.size(); ++i) {
        CHECK(noise.luminance[i] == Approx(40.0).epsilon(0.01));
        CHECK(noise.contrast[i] == Approx(0.15).epsilon(0.08));  // ~700 pooled estimates per tile
    }
    CHECK(noise.meanContrast == Approx(0.15).epsilon(0.03));
}

TEST_CASE("VisibleNoise: a noise-free gradient is not noise, and a pixel without samples is not read",
          "[foveation]") {
    // A linear ramp without noise: the 3x3 leave-one-out mean of a pixel's neighbours is its own
    // value wherever the neighbourhood is symmetric, so the tiles away from the image's border see
    // no noise; the holes (n = 0, holding 1e9) change nothing.
    // (Equal counts keep the neighbourhood's weights symmetric: every pixel at n = 1.)
    VisibleNoiseEstimator estimator(8);
    const NoisyFrame ramp = MakeFrame(48, 48, [](int x, int) { return 10.0 + 2.0 * x; }, [](int, int) { return 0.0; }, 1);
    estimator.Add(ramp.display, Plane<uint16_t>(48, 48, uint16_t(1)));
    for (int ty = 1; ty < 5; ++ty)
        for (int tx = 1; tx < 5; ++tx) CHECK(estimator.Noise().contrast(tx, ty) < 1e-4f);

    // Noise of σ = 4 on a flat 20 with holes: the holes' 1e9 must not reach the estimate.
    VisibleNoiseEstimator withHoles(16);
    const NoisyFrame holed = MakeFrame(64, 64, [](int, int) { return 20.0; }, [](int, int) { return 4.0; }, 3, true);
    withHoles.Add(holed.display, holed.count);
    for (size_t i = 0; i < withHoles.Noise().contrast.size(); ++i) {
        INFO("tile " << i << ": " << withHoles.Noise().luminance[i] << " cd/m2, r " << withHoles.Noise().contrast[i]);
        CHECK(withHoles.Noise().luminance[i] == Approx(20.0).epsilon(0.04));  // 4 standard errors of 448 samples
        CHECK(withHoles.Noise().contrast[i] == Approx(0.2).epsilon(0.12));
    }
}

TEST_CASE("VisibleNoise: frames decay, a new size restarts, no samples is not valid", "[foveation]") {
    VisibleNoiseEstimator estimator(16, 0.5f);
    const Plane<float> zeros(32, 32, 0.0f);
    estimator.Add(zeros, Plane<uint16_t>(32, 32, uint16_t(0)));
    CHECK_FALSE(estimator.Noise().Valid());  // nothing traced yet
    // σ = 2 on 10 for many frames, then σ = 6 on 10: the estimate moves to 0.6 within a few frames.
    auto flat = [](int, int) { return 10.0; };
    for (uint32_t f = 0; f < 6; ++f) {
        const NoisyFrame a = MakeFrame(32, 32, flat, [](int, int) { return 2.0; }, f);
        estimator.Add(a.display, a.count);
    }
    CHECK(estimator.Noise().meanContrast == Approx(0.2).epsilon(0.08));
    for (uint32_t f = 10; f < 20; ++f) {
        const NoisyFrame a = MakeFrame(32, 32, flat, [](int, int) { return 6.0; }, f);
        estimator.Add(a.display, a.count);
    }
    CHECK(estimator.Noise().meanContrast == Approx(0.6).epsilon(0.08));
    const NoisyFrame other = MakeFrame(16, 16, flat, [](int, int) { return 1.0; }, 30);
    estimator.Add(other.display, other.count);
    CHECK(estimator.Noise().Matches(16, 16));
    CHECK(estimator.Noise().meanContrast == Approx(0.1).epsilon(0.2));  // the old frames are gone
}

TEST_CASE("Perceptual noise term: n ∝ S(L) · σ/L under a budget, flat noise unchanged", "[foveation]") {
    const int w = 64, h = 32;
    // A narrow view: the eccentricity hardly varies, and S does not read it anyway.
    const EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(20.0f), float(w) / h), w, h);
    FoveationParams p = Perceptual();
    p.adaptLuminance = 16.0f;
    p.rayBudget = int64_t(w) * h;  // 1 spp: no pixel reaches the bounds
    p.sppFloor = kMinSpp;
    auto model = CreateSppModel(p, RootLuminance);
    p.noiseVisibility = false;
    auto plain = CreateSppModel(p, RootLuminance);
    Plane<float> without, density;
    plain->GenerateDensity(cam, vec3(0, 0, -1), 0, without);

    // No noise known (the first frame, after a cut): the map without the term.
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, density);
    for (size_t i = 0; i < density.size(); ++i) REQUIRE(density[i] == without[i]);
    // Flat noise at the adapting luminance: the same map.
    const VisibleNoise flat = Halves(w, h, 16.0f, 0.3f, 16.0f, 0.3f);
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, density, {nullptr, &flat});
    for (size_t i = 0; i < density.size(); ++i) REQUIRE(density[i] == Approx(without[i]).epsilon(1e-4));

    // Twice the noise contrast on the right: twice the density there (away from the seam, where
    // the tiles' values are interpolated).
    const VisibleNoise noisier = Halves(w, h, 16.0f, 0.2f, 16.0f, 0.4f);
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, density, {nullptr, &noisier});
    CHECK(density(60, 16) / density(3, 16) == Approx(2.0).epsilon(1e-3));
    double total = 0.0;
    for (size_t i = 0; i < density.size(); ++i) total += density[i];
    CHECK(total == Approx(double(w) * h).epsilon(1e-3));  // the budget met

    // The same contrast, four times the luminance on the right: S ∝ √L doubles the density there
    // (the rows are a quarter decade apart: 16 and 64 cd/m² lie between rows, read linearly in log L).
    const VisibleNoise brighter = Halves(w, h, 16.0f, 0.3f, 64.0f, 0.3f);
    model->GenerateDensity(cam, vec3(0, 0, -1), 0, density, {nullptr, &brighter});
    CHECK(density(60, 16) / density(3, 16) == Approx(2.0).epsilon(0.02));

    // The metric's pooling raises S·σ/L to 2pβ/(pβ+2).
    FoveationParams metric = Perceptual();
    metric.rayBudget = p.rayBudget;
    metric.sppFloor = kMinSpp;
    metric.adaptLuminance = 16.0f;
    metric.pooling = "metric";
    const ContrastMasking pooling{1.0, 0.1, 2.0, 2.4, 1.52};
    CreateSppModel(metric, RootLuminance, pooling)->GenerateDensity(cam, vec3(0, 0, -1), 0, density, {nullptr, &noisier});
    const double a = 2.4 * 1.52;
    CHECK(density(60, 16) / density(3, 16) == Approx(std::pow(2.0, 2.0 * a / (a + 2.0))).epsilon(1e-3));
}

TEST_CASE("Perceptual noise term: refusals name the key", "[foveation]") {
    FoveationParams disc;
    disc.noiseVisibility = true;
    CHECK_THROWS_WITH(CreateSppModel(disc), Catch::Contains("foveation.noise_visibility") &&
                                                Catch::Contains("perceptual model only"));
    const EyeCamera cam(Pose(), Fov::FromHorizontal(Radians(60.0f), 1.0f), 32, 32);
    const VisibleNoise other = Halves(16, 32, 10.0f, 0.1f, 10.0f, 0.2f);
    Plane<float> density;
    CHECK_THROWS_WITH(CreateSppModel(Perceptual(), RootLuminance)
                          ->GenerateDensity(cam, vec3(0, 0, -1), 0, density, {nullptr, &other}),
                      Catch::Contains("foveation.noise_visibility") && Catch::Contains("16x32"));
}
