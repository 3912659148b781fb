// Two-history per-pixel maths (SPEC §5): recursions vs explicit sums, the blend factor p vs a
// brute-force minimisation of V(p), V(p) vs Monte-Carlo, constant n ⇒ both histories coincide and p = 1.
#include <cmath>
#include <random>
#include <vector>

#include "denoise/reference/two_history_math.h"
#include "test_support.h"

using namespace fovrt;

namespace {

struct History {
    std::vector<float> n;
    std::vector<float> beta;  // decay applied before frame i's sample (beta[0] unused)
};

History RandomHistory(std::mt19937& rng, bool warmup) {
    std::uniform_int_distribution<int> lenDist(1, 40), nDist(1, 16), kind(0, 2);
    std::uniform_real_distribution<float> alphaDist(0.02f, 0.6f);
    const float alpha = alphaDist(rng);
    History h;
    const int len = lenDist(rng);
    const int mode = kind(rng);  // 0: iid n, 1: two-level (fovea/periphery), 2: runs
    int run = nDist(rng);
    TwoHistoryWeights w;
    for (int i = 0; i < len; ++i) {
        float n = 1;
        if (mode == 0) n = float(nDist(rng));
        if (mode == 1) n = (rng() & 1) ? 8.0f : 1.0f;
        if (mode == 2) {
            if (rng() % 5 == 0) run = nDist(rng);
            n = float(run);
        }
        const float beta = warmup ? TwoHistoryDecay(alpha, w.wu) : 1.0f - alpha;
        w = AccumulateWeights(w, beta, n);
        h.n.push_back(n);
        h.beta.push_back(beta);
    }
    return h;
}

TwoHistoryWeights Accumulate(const History& h) {
    TwoHistoryWeights w;
    for (size_t i = 0; i < h.n.size(); ++i) w = AccumulateWeights(w, h.beta[i], h.n[i]);
    return w;
}

// Weight of sample i in the final history: Π_{j>i} β_j.
std::vector<double> Decays(const History& h) {
    std::vector<double> d(h.n.size(), 1.0);
    for (int i = int(h.n.size()) - 2; i >= 0; --i) d[i] = d[i + 1] * h.beta[i + 1];
    return d;
}

}  // namespace

TEST_CASE("two-history recursions equal the explicit sums", "[two_history]") {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 200; ++trial) {
        const History h = RandomHistory(rng, trial % 2 == 0);
        const TwoHistoryWeights w = Accumulate(h);
        const std::vector<double> d = Decays(h);
        double wu = 0, ww = 0, sm = 0, s0 = 0, s1 = 0;
        for (size_t i = 0; i < h.n.size(); ++i) {
            wu += d[i];
            ww += d[i] * h.n[i];
            sm += d[i] * d[i] / h.n[i];
            s0 += d[i] * d[i];
            s1 += d[i] * d[i] * h.n[i];
        }
        CHECK(w.wu == Approx(wu).epsilon(1e-4));
        CHECK(w.ww == Approx(ww).epsilon(1e-4));
        CHECK(w.sMinus1 == Approx(sm).epsilon(1e-4));
        CHECK(w.s0 == Approx(s0).epsilon(1e-4));
        CHECK(w.s1 == Approx(s1).epsilon(1e-4));

        // The incremental means are the normalised weighted sums of the inputs.
        std::uniform_real_distribution<float> xDist(0.0f, 10.0f);
        float iu = 0, iw = 0;
        double nu = 0, nw = 0;
        TwoHistoryWeights acc;
        for (size_t i = 0; i < h.n.size(); ++i) {
            const float x = xDist(rng);
            acc = AccumulateWeights(acc, h.beta[i], h.n[i]);
            iu = AccumulateUnweighted(iu, x, acc.wu);
            iw = AccumulateWeighted(iw, x, h.n[i], acc.ww);
            nu += d[i] * x;
            nw += d[i] * h.n[i] * x;
        }
        CHECK(iu == Approx(nu / wu).epsilon(1e-4));
        CHECK(iw == Approx(nw / ww).epsilon(1e-4));
    }
}

TEST_CASE("two-history p minimises V(p) by brute force", "[two_history]") {
    std::mt19937 rng(1234);
    int interior = 0;
    for (int trial = 0; trial < 500; ++trial) {
        const History h = RandomHistory(rng, trial % 3 == 0);
        const TwoHistoryWeights w = Accumulate(h);
        const float p = TwoHistoryOptimalBlend(w);
        REQUIRE(p >= 0.0f);
        REQUIRE(p <= 1.0f);
        double best = 1e300, bestP = 0;
        constexpr int kSteps = 20000;
        for (int i = 0; i <= kSteps; ++i) {
            const double pp = double(i) / kSteps;
            const double v = TwoHistoryBlendVariance(w, pp);
            if (v < best) best = v, bestP = pp;
        }
        const double vp = TwoHistoryBlendVariance(w, p);
        INFO("trial " << trial << " p=" << p << " grid argmin=" << bestP << " V(p)=" << vp
                      << " min=" << best);
        CHECK(vp <= best * (1 + 1e-5) + 1e-12);
        // Where V is not flat (distinct n) the minimiser itself must match.
        const double curvature = TwoHistoryBlendVariance(w, 0) + TwoHistoryBlendVariance(w, 1) -
                                 2 * TwoHistoryBlendVariance(w, 0.5);
        if (curvature > 1e-3 * best) {
            CHECK(std::abs(p - bestP) < 2e-3);
            if (bestP > 0.01 && bestP < 0.99) ++interior;
        }
    }
    // The test must exercise the unclamped branch, not only the clamps.
    CHECK(interior > 50);
}

TEST_CASE("the slides' boxed formula (S_0/S_1 swapped) is not the minimiser", "[two_history]") {
    // A fovea/periphery history; the erratum formula must differ from the brute-force optimum.
    History h;
    for (int i = 0; i < 12; ++i) {
        h.n.push_back(i % 3 == 0 ? 8.0f : 1.0f);
        h.beta.push_back(0.9f);
    }
    const TwoHistoryWeights w = Accumulate(h);
    const double wu = w.wu, ww = w.ww;
    const double boxed = std::clamp((wu * wu * w.s0 - wu * ww * w.s1) /
                                        (wu * wu * w.s1 - 2 * wu * ww * w.s1 + ww * ww * w.sMinus1),
                                    0.0, 1.0);
    const float p = TwoHistoryOptimalBlend(w);
    CHECK(TwoHistoryBlendVariance(w, p) < TwoHistoryBlendVariance(w, boxed) * 0.999);
}

TEST_CASE("V(p) matches the Monte-Carlo variance of the blended history", "[two_history]") {
    // x_i is the mean of n_i samples of variance σ² ⇒ Var(x_i) = σ²/n_i.
    History h;
    std::mt19937 rng(99);
    for (int i = 0; i < 30; ++i) {
        h.n.push_back((rng() % 4 == 0) ? 8.0f : ((rng() & 1) ? 2.0f : 1.0f));
        h.beta.push_back(0.85f);
    }
    const TwoHistoryWeights w = Accumulate(h);
    const float p = TwoHistoryOptimalBlend(w);
    std::normal_distribution<float> noise(0.0f, 1.0f);
    constexpr int kTrials = 20000;
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    const float ps[3] = {0.0f, 1.0f, p};
    for (int t = 0; t < kTrials; ++t) {
        TwoHistoryWeights acc;
        float iu = 0, iw = 0;
        for (size_t i = 0; i < h.n.size(); ++i) {
            const float x = 5.0f + noise(rng) / std::sqrt(h.n[i]);
            acc = AccumulateWeights(acc, h.beta[i], h.n[i]);
            iu = AccumulateUnweighted(iu, x, acc.wu);
            iw = AccumulateWeighted(iw, x, h.n[i], acc.ww);
        }
        for (int k = 0; k < 3; ++k) {
            const double b = iw + ps[k] * (iu - iw);
            sum[k] += b;
            sum2[k] += b * b;
        }
    }
    double var[3];
    for (int k = 0; k < 3; ++k) {
        const double m = sum[k] / kTrials;
        var[k] = sum2[k] / kTrials - m * m;
        INFO("p=" << ps[k] << " MC var=" << var[k]
                  << " V(p)=" << TwoHistoryBlendVariance(w, ps[k]));
        CHECK(var[k] == Approx(TwoHistoryBlendVariance(w, ps[k])).epsilon(0.05));
    }
    CHECK(var[2] <= var[0] * 1.02);
    CHECK(var[2] <= var[1] * 1.02);
}

TEST_CASE("constant n: weighted and unweighted histories coincide", "[two_history]") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> xDist(0.0f, 4.0f);
    for (float n : {1.0f, 4.0f, 8.0f, 16.0f}) {
        TwoHistoryWeights w;
        vec3 iu(0), iw(0);
        for (int i = 0; i < 60; ++i) {
            const vec3 x(xDist(rng), xDist(rng), xDist(rng));
            w = AccumulateWeights(w, TwoHistoryDecay(0.2f, w.wu), n);
            iu = AccumulateUnweighted(iu, x, w.wu);
            iw = AccumulateWeighted(iw, x, n, w.ww);
            CHECK(std::abs(iu.x - iw.x) <= 1e-5f * (1 + std::abs(iu.x)));
            CHECK(std::abs(iu.z - iw.z) <= 1e-5f * (1 + std::abs(iu.z)));
            CHECK(w.ww == Approx(n * w.wu).epsilon(1e-5));
        }
    }
}

// Every n of the history equal: V(p) is flat and p is decided by the tie rule, not by the last bits
// of a and c (which favoured p = 0 for some of these histories).
TEST_CASE("a tie of the sample counts gives p = 1", "[two_history]") {
    size_t histories = 0;
    for (float alpha : {0.05f, 0.1f, 0.2f, 0.37f})
        for (int n = 1; n <= 16; ++n) {
            TwoHistoryWeights w;
            for (int frame = 0; frame < 60; ++frame) {
                w = AccumulateWeights(w, TwoHistoryDecay(alpha, w.wu), float(n));
                INFO("alpha " << alpha << ", n " << n << ", frame " << frame);
                REQUIRE(TwoHistoryOptimalBlend(w) == 1.0f);
                ++histories;
            }
        }
    CHECK(histories == 4 * 16 * 60);
}

TEST_CASE("warm-up decay reproduces SVGF's max(alpha, 1/historyLength)", "[two_history]") {
    for (float alpha : {0.05f, 0.1f, 0.2f}) {
        TwoHistoryWeights w;
        for (int len = 1; len <= 60; ++len) {
            w = AccumulateWeights(w, TwoHistoryDecay(alpha, w.wu), 1.0f);
            const float svgf = std::max(alpha, 1.0f / float(len));
            CHECK(1.0f / w.wu == Approx(svgf).epsilon(1e-4));
        }
    }
}

TEST_CASE("gradient EMA and q", "[two_history]") {
    // A step of height h seen by a converged history: g after k frames = h(1 − β_g^k).
    vec3 g(0);
    const vec3 iu(1.0f), x(3.0f);
    for (int k = 1; k <= 5; ++k) {
        g = AccumulateGradient(g, x, iu, 0.8f, true);
        CHECK(g.y == Approx(2.0f * (1.0f - std::pow(0.8f, float(k)))).epsilon(1e-5));
    }
    CHECK(AccumulateGradient(g, x, iu, 0.8f, false).x == 0.0f);
    // The stored scalar: the EMA of lum(x − I_u) is lum of the RGB EMA (lum is linear).
    float gl = 0.0f;
    vec3 g3(0.0f);
    const vec3 steps[3] = {vec3(0.3f, -0.2f, 0.9f), vec3(-1.0f, 0.5f, 0.1f), vec3(2.0f)};
    for (const vec3& d : steps) {
        g3 = AccumulateGradient(g3, iu + d, iu, 0.8f, true);
        gl = AccumulateGradient(gl, LuminanceGradient(iu + d, iu), 0.0f, 0.8f, true);
        CHECK(gl == Approx(Luminance(g3)).margin(1e-6));
    }
    CHECK(TwoHistoryGradientBlend(0.1f, 0.04f, 1.0f) == Approx(0.5f));
    CHECK(TwoHistoryGradientBlend(-0.1f, 0.04f, 1.0f) == Approx(0.5f));  // |g|
    CHECK(TwoHistoryGradientBlend(1.0f, 0.04f, 1.0f) == 1.0f);
    CHECK(TwoHistoryGradientBlend(0.0f, 0.0f, 1.0f) == 0.0f);
    // |lum g| = lum |g| when R, G, B share a sign; smaller otherwise (a hue change).
    const vec3 same(-0.05f, -0.1f, -0.02f), mixed(0.3f, -0.1f, 0.2f);
    CHECK(TwoHistoryGradientBlend(Luminance(same), 0.04f, 1.0f) ==
          Approx(Luminance(glm::abs(same)) / 0.2f));
    CHECK(TwoHistoryGradientBlend(Luminance(mixed), 0.04f, 1.0f) <
          0.5f * Luminance(glm::abs(mixed)) / 0.2f);
    CHECK(TwoHistoryFinalBlend(0.3f, 0.0f) == Approx(0.3f));
    CHECK(TwoHistoryFinalBlend(0.3f, 1.0f) == Approx(1.0f));
    CHECK(TwoHistoryFinalBlend(0.5f, 0.5f) == Approx(0.75f));
}
