// A-SVGF gradient stages (Schied 2018 §3, SPEC §4): scatter (first sample wins, empty strata 0),
// à-trous reconstruction at stratum resolution, λ and α with the 3×3-strata max.
#include <cmath>
#include <random>

#include "denoise/reference/asvgf_ref.h"
#include "denoise/denoiser_factory.h"
#include "denoise/reference/two_history_ref.h"
#include "denoise_two_history_scene.h"
#include "test_support.h"

using namespace fovrt;

namespace {

GradientSample Sample(int px, int py, float fNew, float fOld) {
    GradientSample s;
    s.pixel = ivec2(px, py);
    s.prevPixel = s.pixel;
    s.stratum = s.pixel / kGradientStratumSize;
    s.newLuminance = fNew;
    s.oldLuminance = fOld;
    return s;
}

}  // namespace

TEST_CASE("asvgf scatter: first sample per stratum wins, empty strata are 0", "[asvgf]") {
    FrameInputs f;
    test::MakeStaticPlane(f, 10, 7, 1);
    CHECK(StratumGridSize(10, 7) == ivec2(4, 3));
    f.gradientSamples = {Sample(1, 1, 2.0f, 0.5f), Sample(2, 2, 9.0f, 9.0f),
                         Sample(9, 6, 0.25f, 1.0f), Sample(50, 1, 1.0f, 0.0f)};
    f.gradientSamples[3].stratum = ivec2(16, 0);  // outside the grid: ignored
    Plane<vec2> g;
    Plane<StratumGuide> guide;
    CHECK(AsvgfScatterGradientsRef(f, g, guide) == 2);
    CHECK(g(0, 0) == vec2(1.5f, 2.0f));
    CHECK(g(3, 2) == vec2(-0.75f, 1.0f));
    CHECK(g(1, 1) == vec2(0.0f));
    CHECK(guide(0, 0).objectId == 0u);
}

TEST_CASE("asvgf reconstruction: uniform change gives exact lambda despite empty strata",
          "[asvgf]") {
    // Half the strata hold a sample whose luminance dropped from 1 to 0.25: δ̂/Δ̂ stays 0.75
    // everywhere because empty strata dilute δ and Δ alike.
    FrameInputs f;
    test::MakeStaticPlane(f, 30, 30, 1);
    std::mt19937 rng(3);
    for (int sy = 0; sy < 10; ++sy)
        for (int sx = 0; sx < 10; ++sx)
            if ((sx + sy) % 2 == 0)
                f.gradientSamples.push_back(
                    Sample(sx * 3 + int(rng() % 3), sy * 3 + int(rng() % 3), 0.25f, 1.0f));
    Plane<float> alpha, lambda;
    Plane<vec2> recon;
    AsvgfParams params;
    AsvgfTemporalAlphaRef(f, params, SvgfParams{}, alpha, lambda, &recon);
    for (int sy = 0; sy < 10; ++sy)
        for (int sx = 0; sx < 10; ++sx) {
            CHECK(recon(sx, sy).y > 0.0f);
            CHECK(std::abs(recon(sx, sy).x) / recon(sx, sy).y == Approx(0.75f).epsilon(1e-4));
        }
    CHECK(lambda(17, 4) == Approx(0.75f).epsilon(1e-4));
    CHECK(alpha(17, 4) == Approx(0.25f * 0.1f + 0.75f).epsilon(1e-4));
}

TEST_CASE("asvgf alpha: no change keeps the base alpha, a local change spreads by one stratum",
          "[asvgf]") {
    constexpr int kS = 8;  // 8×8 strata
    Plane<vec2> recon(kS, kS, vec2(0.0f, 1.0f));
    recon(4, 4) = vec2(-2.0f, 1.0f);  // |δ̂| > Δ̂ clamps λ to 1
    recon(1, 6) = vec2(0.5f, 0.0f);   // Δ̂ = 0: λ = 0, no division by zero
    Plane<float> alpha, lambda;
    AsvgfAlphaRef(recon, kS * 3, kS * 3, 0.1f, alpha, lambda);
    CHECK(alpha(0, 0) == Approx(0.1f));
    CHECK(alpha(4, 19) == Approx(0.1f));
    for (int y = 9; y < 18; ++y)
        for (int x = 9; x < 18; ++x)
            CHECK(alpha(x, y) == Approx(1.0f));  // strata 3..5: max picks (4,4)
    CHECK(alpha(8, 12) == Approx(0.1f));         // stratum (2, 4): two strata away
    CHECK(alpha(18, 12) == Approx(0.1f));        // stratum (6, 4)
}

TEST_CASE("asvgf reconstruction respects geometric edges", "[asvgf]") {
    // Two objects at different depths: a change on the left object must not raise λ on the right.
    FrameInputs f;
    test::MakeStaticPlane(f, 48, 24, 1);
    for (int y = 0; y < 24; ++y)
        for (int x = 24; x < 48; ++x) {
            f.linearDepth(x, y) = 6.0f;
            f.objectId(x, y) = 1;
        }
    for (int sy = 0; sy < 8; ++sy)
        for (int sx = 0; sx < 16; ++sx)
            f.gradientSamples.push_back(Sample(sx * 3 + 1, sy * 3 + 1, sx < 8 ? 0.1f : 1.0f, 1.0f));
    Plane<float> alpha, lambda;
    AsvgfTemporalAlphaRef(f, AsvgfParams{}, SvgfParams{}, alpha, lambda);
    CHECK(lambda(3, 12) == Approx(0.9f).epsilon(1e-3));
    CHECK(lambda(40, 12) == Approx(0.0f).margin(1e-4));
    // The 3×3-strata max still reaches one stratum across the edge (SPEC §4).
    CHECK(lambda(25, 12) == Approx(0.9f).epsilon(1e-3));
}

TEST_CASE("asvgf denoiser: no gradient samples behaves like SVGF with alpha 0.1", "[asvgf]") {
    DenoiserParams params;
    params.svgf.alphaColor = params.asvgf.alpha;
    params.svgf.alphaMoments = params.asvgf.alpha;
    auto asvgf = CreateDenoiser("asvgf", "cpu", params);
    CHECK(asvgf->Name() == "asvgf");
    auto svgf = test::MakeSvgf(params.svgf);
    std::mt19937 rng(11);
    std::normal_distribution<float> g(0.0f, 0.3f);
    FrameInputs f;
    Plane<vec3> a, b;
    double maxRel = 0;
    for (uint32_t frame = 0; frame < 15; ++frame) {
        test::MakeStaticPlane(f, 24, 24, frame);
        for (size_t i = 0; i < f.direct.size(); ++i) f.direct[i] = vec3(2.0f + g(rng));
        asvgf->Denoise(f, a);
        svgf.Denoise(f, b);
        for (size_t i = 0; i < a.size(); ++i)
            maxRel = std::max(maxRel, double(std::abs(a[i].x - b[i].x) / b[i].x));
    }
    INFO("max relative difference " << maxRel);
    CHECK(maxRel < 1e-4);
}
