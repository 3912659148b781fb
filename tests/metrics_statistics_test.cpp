// Robust summaries and the paired block-bootstrap ratio (metrics/statistics.h): closed forms
// first, then the interval's coverage on synthetic per-frame data with a known difference, and
// the widening that blocks give on autocorrelated frames.
#include <algorithm>
#include <cmath>
#include <vector>

#include "metrics/statistics.h"
#include "test_support.h"

using namespace fovrt;

namespace {

// Standard normal deviates (Box–Muller on a fixed PCG stream).
class Normal {
public:
    explicit Normal(uint64_t seed) : rng_(seed) {}
    double operator()() {
        const double u1 = (double(rng_.Next()) + 1.0) / 4294967297.0;
        const double u2 = double(rng_.Next()) / 4294967296.0;
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
    }

private:
    Pcg32 rng_;
};

// A stationary AR(1) series with unit variance: x_t = φ x_{t−1} + √(1 − φ²) ε_t.
std::vector<double> Ar1(Normal& normal, size_t n, double phi) {
    std::vector<double> x(n);
    double v = normal();
    for (size_t t = 0; t < n; ++t) {
        x[t] = v;
        v = phi * v + std::sqrt(1.0 - phi * phi) * normal();
    }
    return x;
}

// Per-frame errors of a baseline and of a variant whose per-frame log ratio to it is
// ln(trueRatio) + σ·noise (noise AR(1) with coefficient φ), per (seed, eye) sequence. The
// baseline itself varies over frames by a factor of ~100 (a light in the fovea), which the
// ratio must not care about.
std::vector<PairedSequence> Synthetic(Normal& normal, int sequences, size_t frames, double trueRatio,
                                      double sigma, double phi) {
    std::vector<PairedSequence> out;
    for (int s = 0; s < sequences; ++s) {
        PairedSequence p;
        std::vector<double> noise = Ar1(normal, frames, phi);
        for (size_t t = 0; t < frames; ++t) {
            const double base = 1e-3 * std::exp(2.3 * normal());
            p.baseline.push_back(base);
            p.variant.push_back(base * trueRatio * std::exp(sigma * noise[t]));
        }
        out.push_back(std::move(p));
    }
    return out;
}

}  // namespace

TEST_CASE("mean, median and geometric mean of a closed-form sample", "[metrics][statistics]") {
    Spread s = Summarize({1.0, 2.0, 4.0, std::nan("")});
    CHECK(s.count == 3u);
    CHECK(s.mean == Approx(7.0 / 3.0));
    CHECK(s.median == Approx(2.0));
    CHECK(s.geometricMean == Approx(2.0));
    CHECK(Summarize({1.0, 3.0}).median == Approx(2.0));
    CHECK(std::isnan(Summarize({0.5, -0.1}).geometricMean));  // undefined with a value ≤ 0
    CHECK(Summarize({}).count == 0u);
    CHECK(Quantile({4.0, 1.0, 3.0, 2.0}, 0.25) == Approx(1.75));
}

TEST_CASE("paired ratio: a variant exactly half the baseline on every frame", "[metrics][statistics]") {
    std::vector<PairedSequence> seqs(2);
    for (int t = 0; t < 30; ++t)
        for (auto& s : seqs) {
            const double base = 0.01 * (1 + t % 7);
            s.baseline.push_back(base);
            s.variant.push_back(0.5 * base);
        }
    seqs[1].baseline.push_back(0.0);  // dropped: a ratio needs positive values
    seqs[1].variant.push_back(0.1);
    PairedRatio r = ComparePaired(seqs, Better::kLower);
    CHECK(r.ratio == Approx(0.5));
    CHECK(r.lower == Approx(0.5));
    CHECK(r.upper == Approx(0.5));
    CHECK(r.winRate == 1.0);
    CHECK(r.pairs == 60u);
    CHECK(r.dropped == 1u);
    CHECK(r.Significant());
    // For a similarity (higher is better) the same numbers are a loss.
    CHECK(ComparePaired(seqs, Better::kHigher).winRate == 0.0);
}

TEST_CASE("paired ratio: ties count one half, no change is not significant", "[metrics][statistics]") {
    Normal normal(7);
    std::vector<PairedSequence> seqs = Synthetic(normal, 2, 80, 1.0, 0.3, 0.0);
    for (size_t t = 0; t < 10; ++t) seqs[0].variant[t] = seqs[0].baseline[t];  // exact ties
    PairedRatio r = ComparePaired(seqs, Better::kLower);
    CHECK(r.lower < 1.0);
    CHECK(r.upper > 1.0);
    CHECK_FALSE(r.Significant());
    CHECK(r.winRate > 0.35);
    CHECK(r.winRate < 0.65);
    // Float noise is no difference: a variant equal to the baseline up to 1e-9 is all ties.
    std::vector<PairedSequence> same = seqs;
    for (auto& s : same)
        for (size_t t = 0; t < s.variant.size(); ++t) s.variant[t] = s.baseline[t] * (1.0 + (t % 2 ? 1e-9 : -1e-9));
    PairedRatio noise = ComparePaired(same, Better::kLower);
    CHECK(noise.ratio == 1.0);
    CHECK(noise.winRate == 0.5);
    CHECK_FALSE(noise.Significant());
    // Reproducible: the bootstrap's RNG seed is fixed.
    PairedRatio again = ComparePaired(seqs, Better::kLower);
    CHECK(again.lower == r.lower);
    CHECK(again.upper == r.upper);
}

TEST_CASE("the bootstrap interval covers a known ratio at the nominal 95 % rate", "[metrics][statistics]") {
    // 1,000 synthetic experiments (2 eye sequences × 100 frames, iid per-frame noise) whose true
    // geometric-mean ratio is 0.8; the 95 % interval must contain 0.8 in 92–98 % of them.
    Normal normal(2024);
    BootstrapOptions options;
    options.resamples = 999;
    int covered = 0, significant = 0;
    const int trials = 1000;
    for (int trial = 0; trial < trials; ++trial) {
        options.rngSeed = 1000u + uint64_t(trial);
        PairedRatio r = ComparePaired(Synthetic(normal, 2, 100, 0.8, 0.6, 0.0), Better::kLower, options);
        covered += (r.lower <= 0.8 && 0.8 <= r.upper) ? 1 : 0;
        significant += r.Significant() ? 1 : 0;
    }
    const double coverage = double(covered) / trials;
    INFO("coverage " << coverage);
    CHECK(coverage >= 0.92);
    CHECK(coverage <= 0.98);
    CHECK(significant > trials * 9 / 10);  // a 20 % difference is found almost always
}

TEST_CASE("blocks widen the interval on autocorrelated frames; iid resampling is too narrow",
          "[metrics][statistics]") {
    // AR(1) per-frame noise with φ = 0.8 (a denoiser's history carries errors over frames).
    Normal normal(99);
    const int trials = 300;
    double widthBlock = 0.0, widthIid = 0.0;
    int coveredBlock = 0, coveredIid = 0, blockSum = 0;
    BootstrapOptions automatic, iid;
    automatic.resamples = iid.resamples = 999;
    iid.blockLength = 1;
    for (int trial = 0; trial < trials; ++trial) {
        std::vector<PairedSequence> seqs = Synthetic(normal, 2, 120, 0.9, 0.3, 0.8);
        PairedRatio b = ComparePaired(seqs, Better::kLower, automatic);
        PairedRatio i = ComparePaired(seqs, Better::kLower, iid);
        widthBlock += std::log(b.upper / b.lower);
        widthIid += std::log(i.upper / i.lower);
        coveredBlock += (b.lower <= 0.9 && 0.9 <= b.upper) ? 1 : 0;
        coveredIid += (i.lower <= 0.9 && 0.9 <= i.upper) ? 1 : 0;
        blockSum += b.blockLength;
    }
    INFO("mean block " << double(blockSum) / trials << ", coverage block " << double(coveredBlock) / trials
                       << ", iid " << double(coveredIid) / trials << ", width ratio " << widthBlock / widthIid);
    CHECK(double(blockSum) / trials > 3.0);
    // √((1+φ)/(1−φ)) = 3 for the long-run s.d.: blocks recover much of it.
    CHECK(widthBlock > 1.8 * widthIid);
    CHECK(coveredIid < trials * 8 / 10);  // iid resampling badly under-covers
    CHECK(coveredBlock > coveredIid + trials / 10);
}

TEST_CASE("automatic block length: 1 for iid frames, longer for correlated ones", "[metrics][statistics]") {
    // The rule is an estimate: averaged over 50 draws of 2 × 200 frames.
    Normal normal(5);
    double iid = 0.0, correlated = 0.0;
    int longest = 0;
    for (int draw = 0; draw < 50; ++draw) {
        iid += AutomaticBlockLength({Ar1(normal, 200, 0.0), Ar1(normal, 200, 0.0)}) / 50.0;
        const int b = AutomaticBlockLength({Ar1(normal, 200, 0.9), Ar1(normal, 200, 0.9)});
        correlated += b / 50.0;
        longest = std::max(longest, b);
    }
    INFO("mean block length: iid " << iid << ", AR(1) 0.9 " << correlated);
    CHECK(iid < 2.0);
    CHECK(correlated > 8.0);
    CHECK(longest <= 42);  // ceil(min(3√200, 200/3))
    CHECK(AutomaticBlockLength({{1.0, 2.0}}) == 1);              // too short to estimate
    CHECK(AutomaticBlockLength({std::vector<double>(50, 3.0)}) == 1);  // constant
}

TEST_CASE("block bootstrap means: a constant stays constant, blocks of n keep the sample mean",
          "[metrics][statistics]") {
    auto means = BlockBootstrapMeans({std::vector<double>(10, 2.0)}, 3, 50, 1);
    REQUIRE(means.size() == 50u);
    for (double m : means) CHECK(m == Approx(2.0));
    // A circular block as long as the sequence is a rotation of it: the mean never changes.
    for (double m : BlockBootstrapMeans({{1.0, 2.0, 3.0, 10.0}}, 4, 20, 3)) CHECK(m == Approx(4.0));
}

TEST_CASE("dominant values: the frames that hold most of a mean", "[metrics][statistics]") {
    DominantSet d = DominantValues({1.0, 1.0, 95.0, 1.0, 2.0}, 0.5);
    REQUIRE(d.indices.size() == 1u);
    CHECK(d.indices[0] == 2u);
    CHECK(d.share == Approx(0.95));
    DominantSet even = DominantValues({1.0, 1.0, 1.0, 1.0}, 0.5);
    CHECK(even.indices.size() == 2u);
    CHECK(DominantValues({}, 0.5).indices.empty());
}
