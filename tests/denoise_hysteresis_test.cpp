// The hysteresis variants (two-history-hysteresis, two-history-stable-hysteresis;
// denoise/two_history_stable.md), C++ reference: the held choice's closed form, the choice stage's
// restarts, rate 1 with band 0 giving two-history itself, a pixel whose choice p alternates frame
// to frame (the blend's output held), and the thesis protocol's moving fovea at 64×64.
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "denoise/denoiser_factory.h"
#include "denoise/reference/two_history_choice_ref.h"
#include "denoise/reference/two_history_math.h"
#include "denoise_moving_fovea.h"
#include "denoise_two_history_scene.h"
#include "test_support.h"

using namespace fovrt;
using namespace fovrt::test;

TEST_CASE("hysteresis variants: the held choice's closed form", "[hysteresis]") {
    SECTION("rate 1 and band 0 return p") {
        for (float p : {0.0f, 0.3f, 1.0f}) CHECK(HystereticChoice(0.7f, p, 1.0f, 0.0f) == Approx(p));
    }
    SECTION("within the band the choice is held") {
        CHECK(HystereticChoice(0.5f, 0.55f, 1.0f, 0.1f) == 0.5f);
        CHECK(HystereticChoice(0.5f, 0.41f, 0.25f, 0.1f) == 0.5f);
    }
    SECTION("beyond the band it moves by rate times the excess, towards p") {
        CHECK(HystereticChoice(0.2f, 0.8f, 0.25f, 0.1f) == Approx(0.2f + 0.25f * 0.5f));
        CHECK(HystereticChoice(0.8f, 0.2f, 0.25f, 0.1f) == Approx(0.8f - 0.25f * 0.5f));
        CHECK(HystereticChoice(0.2f, 0.8f, 1.0f, 0.1f) == Approx(0.7f));  // stops a band short of p
    }
    SECTION("a p alternating 0, 1 moves an unbanded choice by rate/(2 - rate), a banded one less") {
        for (float band : {0.0f, 0.2f}) {
            float held = 0.5f, last = 0.0f, swing = 0.0f;
            for (int frame = 0; frame < 200; ++frame) {
                last = held;
                held = HystereticChoice(held, float(frame % 2), 0.25f, band);
                swing = std::abs(held - last);
            }
            const float unbanded = 0.25f / (2.0f - 0.25f);  // 1/7
            if (band == 0.0f) CHECK(swing == Approx(unbanded).margin(1e-5));
            else CHECK(swing < unbanded);
        }
    }
}

TEST_CASE("hysteresis variants: the choice stage holds the reprojected choice and restarts where it must",
          "[hysteresis]") {
    FrameInputs f, last;
    MakeStaticPlane(f, 4, 4, 1);
    MakeStaticPlane(last, 4, 4, 0);
    // A state whose p lies inside (0, 1): W_u = 10, W_w = 30, S = (2, 5, 40).
    Plane<float> wu(4, 4, 10.0f), ww(4, 4, 30.0f), prev(4, 4, 0.0f), cur;
    Plane<vec3> s(4, 4, vec3(2.0f, 5.0f, 40.0f));
    const float p = TwoHistoryOptimalBlend(StoredTwoHistoryWeights(10.0f, 30.0f, vec3(2.0f, 5.0f, 40.0f)));
    REQUIRE(p > 0.2f);
    REQUIRE(p < 1.0f);
    TwoHistoryParams params;
    params.choiceRate = 0.25f;
    params.choiceBand = 0.1f;
    SECTION("with a previous frame: HystereticChoice of the reprojected choice") {
        TwoHistoryChoiceRef(f, GeometryOf(last), true, prev, wu, ww, s, params, Precision::Fp32, cur);
        CHECK(cur(2, 1) == Approx(HystereticChoice(0.0f, p, 0.25f, 0.1f)));
        CHECK(cur(2, 1) == Approx(0.25f * (p - 0.1f)));
    }
    SECTION("first frame, restarted accumulation (W_u = 1), failed reprojection: p") {
        TwoHistoryChoiceRef(f, GeometryOf(last), false, prev, wu, ww, s, params, Precision::Fp32, cur);
        CHECK(cur(2, 1) == Approx(p));
        wu(2, 1) = 1.0f;
        TwoHistoryChoiceRef(f, GeometryOf(last), true, prev, wu, ww, s, params, Precision::Fp32, cur);
        CHECK(cur(2, 1) == Approx(TwoHistoryOptimalBlend(StoredTwoHistoryWeights(1.0f, 30.0f, s(2, 1)))));
        CHECK(cur(1, 1) == Approx(0.25f * (p - 0.1f)));
        f.objectId(3, 3) = 7;  // another object than last frame's: no tap survives
        TwoHistoryChoiceRef(f, GeometryOf(last), true, prev, Plane<float>(4, 4, 10.0f), ww, s, params,
                            Precision::Fp32, cur);
        CHECK(cur(3, 3) == Approx(p));
    }
}

TEST_CASE("hysteresis variants: rate 1 and band 0 are two-history", "[hysteresis]") {
    DenoiserParams params;
    params.twoHistory.choiceRate = 1.0f;
    params.twoHistory.choiceBand = 0.0f;
    // A fovea edge sweeping across: p changes where the sample counts do.
    const auto sweep = [](int x, int frame) { return x < 16 + frame ? 8 : 1; };
    CHECK(WorstOutputDifference("two-history", "two-history-hysteresis", params, sweep) < 1e-5);
}

TEST_CASE("hysteresis variants: a pixel whose history choice alternates gives a stable output", "[hysteresis]") {
    // The state alternates between two (W_u, W_w, S) whose choices p differ by less than the band;
    // I_u = 1 and I_w = 2 everywhere, q = 0: two-history's blend 2 − p alternates, the held one not.
    FrameInputs f, last;
    MakeStaticPlane(f, 4, 4, 1);
    MakeStaticPlane(last, 4, 4, 0);
    const vec3 sA(2.0f, 5.0f, 40.0f), sB(2.0f, 5.0f, 20.0f);
    const float pA = TwoHistoryOptimalBlend(StoredTwoHistoryWeights(10.0f, 30.0f, sA));
    const float pB = TwoHistoryOptimalBlend(StoredTwoHistoryWeights(10.0f, 30.0f, sB));
    TwoHistoryParams params;  // defaults: rate 0.25, band 0.3
    REQUIRE(std::abs(pA - pB) > 0.2f);
    REQUIRE(std::abs(pA - pB) < params.choiceBand);
    Plane<float> wu(4, 4, 10.0f), ww(4, 4, 30.0f), q(4, 4, 0.0f), prev(4, 4, 0.0f), cur;
    Plane<vec3> s;
    const Plane<vec4> iu(4, 4, vec4(1.0f)), iw(4, 4, vec4(2.0f));
    Plane<vec4> plain, held;
    for (int frame = 0; frame < 10; ++frame) {
        s = Plane<vec3>(4, 4, frame % 2 ? sB : sA);
        TwoHistoryChoiceRef(f, GeometryOf(last), frame > 0, prev, wu, ww, s, params, Precision::Fp32, cur);
        TwoHistoryBlendRef(iu, iw, wu, ww, s, q, plain);
        TwoHistoryBlendRef(iu, iw, wu, ww, s, q, held, {}, &cur);
        CHECK(plain(1, 2).x == Approx(2.0f - (frame % 2 ? pB : pA)));  // the thesis variant alternates
        CHECK(held(1, 2).x == Approx(2.0f - pA));                       // held from the first frame on
        std::swap(prev, cur);
    }
}

TEST_CASE("hysteresis variants: moving fovea over a static view (thesis protocol, 64x64)", "[hysteresis]") {
    DenoiserParams params;  // the thesis preset: α = 0.05, 2 iterations, feedback after the first
    params.svgf.alphaColor = params.svgf.alphaMoments = 0.05f;
    params.svgf.atrousIterations = 2;
    params.svgf.feedbackIteration = 1;
    enum { Svgf, TwoHistory, Hysteresis, Stable, StableHysteresis };
    const FoveaScores r = MovingFoveaScores({"svgf", "two-history", "two-history-hysteresis", "two-history-stable",
                                             "two-history-stable-hysteresis"},
                                            params);
    CHECK(r.temporal[TwoHistory] > r.temporal[Svgf]);  // the flicker the variants address
    CHECK(r.temporal[Hysteresis] < 0.9 * r.temporal[TwoHistory]);
    CHECK(r.relMse[Hysteresis] < r.relMse[Svgf]);
    // With the stabilisation: below SVGF's foveal flicker and error, and below two-history-stable's flicker.
    CHECK(r.temporal[StableHysteresis] <= r.temporal[Svgf]);
    CHECK(r.relMse[StableHysteresis] < r.relMse[Svgf]);
    CHECK(r.temporal[StableHysteresis] < 0.85 * r.temporal[Stable]);
}
