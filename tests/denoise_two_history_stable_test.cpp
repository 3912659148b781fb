// two-history-stable (denoise/two_history_stable.md), C++ reference: the stabilisation stage
// against the closed form of an EMA of an alternating input (a pixel whose history choice flips
// every frame), the clamp's role, sample counts alternating every frame, and the thesis protocol's
// static view under a moving fovea (scaled to 64×64): less foveal flicker than two-history (no
// more than SVGF's with a longer stabilisation) with a foveal relMSE still below SVGF's.
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "denoise/denoiser_factory.h"
#include "denoise/reference/two_history_stable_ref.h"
#include "denoise_moving_fovea.h"
#include "denoise_two_history_scene.h"
#include "metrics/image_metrics.h"
#include "test_support.h"

using namespace fovrt;
using namespace fovrt::test;  // the moving-fovea fixture (test_support.h)

namespace {

// The stage on a static uniform 8×8 plane whose filtered illumination alternates between grey
// levels a (even frames) and b (odd frames), as the blend's output does where t flips between the
// two histories; returns the centre pixel's stabilised luminance of the last two frames (even,
// odd; `frames` is even).
std::pair<float, float> AlternatingPixel(float a, float b, float variance, const TwoHistoryStableParams& params,
                                         int frames) {
    FrameInputs f;
    MakeStaticPlane(f, 8, 8, 0);
    Plane<float> wu(8, 8, 20.0f), prev(8, 8, 0.0f), cur;
    Plane<vec4> filtered(8, 8), out;
    float last = 0.0f, beforeLast = 0.0f;
    for (int frame = 0; frame < frames; ++frame) {
        const float level = frame % 2 ? b : a;
        for (size_t i = 0; i < filtered.size(); ++i) filtered[i] = vec4(vec3(level), variance);
        TwoHistoryStabilizeRef(filtered, f, GeometryOf(f), frame > 0, prev, wu, params, Precision::Fp32, cur, out);
        std::swap(prev, cur);
        beforeLast = last;
        last = Luminance(vec3(out(4, 4)));
        CHECK(Luminance(vec3(out(4, 4))) == Approx(prev(4, 4)).margin(1e-6));  // out carries L_s
    }
    return {beforeLast, last};
}

}  // namespace

TEST_CASE("two-history-stable: a pixel whose history choice alternates gives a stable output",
          "[two_history_stable]") {
    const float a = 1.0f, b = 2.0f, d = b - a;
    TwoHistoryStableParams params;
    params.alpha = 0.2f;
    SECTION("unclamped: the EMA's steady alternation d·α/(2 − α), not d") {
        params.sigmaScale = 4.0f;  // σ = 0.5: the window m ± 2 holds both levels
        const auto [even, odd] = AlternatingPixel(a, b, 0.25f, params, 62);
        const float amplitude = params.alpha / (2.0f - params.alpha) * d;  // 1/9 at α = 0.2
        CHECK(std::abs(odd - even) == Approx(amplitude).margin(1e-4));
        CHECK(0.5f * (odd + even) == Approx(0.5f * (a + b)).margin(1e-4));  // unbiased
    }
    SECTION("k = 0 pins the history to the neighbourhood: the input passes through") {
        params.sigmaScale = 0.0f;
        const auto [even, odd] = AlternatingPixel(a, b, 0.25f, params, 62);
        CHECK(even == Approx(a).margin(1e-5));
        CHECK(odd == Approx(b).margin(1e-5));
    }
    SECTION("a change beyond k standard deviations is followed, not lagged") {
        params.sigmaScale = 1.0f;  // σ = 0.1, d = 1: the history is clamped to b − 0.1
        const auto [even, odd] = AlternatingPixel(a, b, 0.01f, params, 62);
        CHECK(odd == Approx(b - 0.1f * (1.0f - params.alpha)).margin(1e-5));
        CHECK(even == Approx(a + 0.1f * (1.0f - params.alpha)).margin(1e-5));
    }
}

TEST_CASE("two-history-stable: sample counts alternating every frame flicker less than two-history",
          "[two_history_stable]") {
    // n = 1 and n = 32 on alternate frames: the weighted history takes most of each 32-spp frame
    // (weight 32/W_w), so two-history's output jumps every other frame.
    DenoiserParams params;
    params.svgf.alphaColor = params.svgf.alphaMoments = 0.05f;
    params.svgf.atrousIterations = 2;
    double temporal[2] = {0.0, 0.0};
    const char* names[2] = {"two-history", "two-history-stable"};
    for (int v = 0; v < 2; ++v) {
        auto denoiser = CreateDenoiser(names[v], "cpu", params);
        std::mt19937 rng(7);
        FrameInputs f;
        Plane<vec3> out, prev;
        for (int frame = 0; frame < 60; ++frame) {
            NoisyFrame(f, 32, 32, uint32_t(frame), 1.0f, [&](int, int) { return frame % 2 ? 32 : 1; }, rng, 0.0f);
            denoiser->Denoise(f, out);
            if (frame >= 30) temporal[v] += TemporalError(out, prev);
            prev = out;
        }
    }
    std::printf("alternating n = 1 / 32: mean |dlum| frames 30..59: two-history %.5f two-history-stable %.5f\n",
                temporal[0] / 30, temporal[1] / 30);
    CHECK(temporal[1] < 0.5 * temporal[0]);
}

namespace {

// svgf, two-history, two-history-stable on the moving fovea (denoise_moving_fovea.h), in that order.
FoveaScores MovingFovea(const DenoiserParams& params) {
    std::printf("alpha_s %.2f: ", params.twoHistoryStable.alpha);
    return MovingFoveaScores({"svgf", "two-history", "two-history-stable"}, params);
}

}  // namespace

TEST_CASE("two-history-stable: moving fovea over a static view (thesis protocol, 64x64)", "[two_history_stable]") {
    DenoiserParams params;  // the thesis preset: α = 0.05, 2 iterations, feedback after the first
    params.svgf.alphaColor = params.svgf.alphaMoments = 0.05f;
    params.svgf.atrousIterations = 2;
    params.svgf.feedbackIteration = 1;
    SECTION("default alpha_s: two-history's foveal flicker cut by > 40 %, relMSE still below SVGF's") {
        const FoveaScores r = MovingFovea(params);
        CHECK(r.temporal[1] > r.temporal[0]);  // the flicker the variant removes
        CHECK(r.temporal[2] < 0.6 * r.temporal[1]);
        CHECK(r.relMse[2] < r.relMse[0]);
    }
    // Every sample here is N(truth, 1/n) on a truth of ~3: far noisier per sample than the scenes
    // (app_two_history_stable_test holds the default to SVGF's flicker on the thesis preset's
    // cornell); a longer stabilisation gets below SVGF's flicker here too, and keeps an error gain.
    SECTION("alpha_s = 0.1: foveal flicker no higher than SVGF's, relMSE below SVGF's") {
        params.twoHistoryStable.alpha = 0.1f;
        const FoveaScores r = MovingFovea(params);
        CHECK(r.temporal[2] <= r.temporal[0]);
        CHECK(r.relMse[2] < r.relMse[0]);
    }
}
