// Rays saved at equal JOD and JOD gain at equal rays (metrics/rate_quality.h): closed forms first
// (a curve shifted in rate by k saves k, one shifted in JOD by c gains c, identical curves give 1
// and 0, also over a partial overlap; a point k× cheaper saves k), then the documented no-results, the PCHIP interpolant
// against hand-computed Fritsch–Carlson slopes, and the paired seed bootstrap interval.
#include <cmath>
#include <string>
#include <vector>

#include "metrics/rate_quality.h"
#include "test_support.h"

using namespace fovrt;

namespace {

// Two sweep shapes: a saturating JOD on doubling budgets, and an irregular one.
const std::vector<RateQualityCurve> kShapes = {
    {{1.0, 5.0}, {2.0, 6.2}, {4.0, 7.1}, {8.0, 7.8}, {16.0, 8.3}, {32.0, 8.6}},
    {{0.5, 3.0}, {0.9, 5.0}, {3.0, 6.0}, {3.5, 8.5}, {20.0, 9.0}},
};

// The curve with every point's rays divided by k (the same JOD with k× fewer rays).
RateQualityCurve FewerRays(const RateQualityCurve& curve, double k) {
    RateQualityCurve out = curve;
    for (RateQualityPoint& p : out) p.rays /= k;
    return out;
}

RateQualityCurve HigherJod(const RateQualityCurve& curve, double c) {
    RateQualityCurve out = curve;
    for (RateQualityPoint& p : out) p.jod += c;
    return out;
}

// Points on ln R = a + b·Q (where PCHIP and the cubic are exact) at the given JOD knots.
RateQualityCurve LogLinear(const std::vector<double>& jods, double a, double b) {
    RateQualityCurve out;
    for (double q : jods) out.push_back({std::exp(a + b * q), q});
    return out;
}

bool Near(double value, double expected, double tolerance = 1e-9) {
    return std::abs(value - expected) <= tolerance * std::max(1.0, std::abs(expected));
}

bool Contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("a curve with k times fewer rays at the same JOD saves k, with either fit", "[rate_quality]") {
    for (const RateQualityCurve& anchor : kShapes)
        for (double k : {0.5, 1.37, 2.0, 4.0}) {
            for (RateQualityFit fit : {RateQualityFit::kPchip, RateQualityFit::kCubic}) {
                const BjontegaardResult r = RaysSavedAtEqualJod(anchor, FewerRays(anchor, k), fit);
                INFO("k = " << k << ", fit " << int(fit) << ": " << r.reason);
                REQUIRE(r.Ok());
                CHECK(Near(r.value, k));
                CHECK(r.from == anchor.front().jod);
                CHECK(r.to == anchor.back().jod);
            }
        }
}

TEST_CASE("a log-linear curve saves k on other JOD knots and over a partial overlap", "[rate_quality]") {
    const RateQualityCurve anchor = LogLinear({3.0, 4.0, 6.0, 7.0, 9.0}, 0.2, 0.45);
    for (double k : {0.7, 2.0, 3.3}) {
        const RateQualityCurve test = LogLinear({3.5, 5.0, 8.2, 9.5}, 0.2 - std::log(k), 0.45);
        for (RateQualityFit fit : {RateQualityFit::kPchip, RateQualityFit::kCubic}) {
            const BjontegaardResult r = RaysSavedAtEqualJod(anchor, test, fit);
            INFO("k = " << k << ": " << r.reason);
            REQUIRE(r.Ok());
            CHECK(Near(r.value, k));
            CHECK(r.from == 3.5);  // the overlap: the test starts later, the anchor ends earlier
            CHECK(r.to == 9.0);
        }
    }
}

TEST_CASE("a curve c JOD higher at the same rays gains c JOD", "[rate_quality]") {
    for (const RateQualityCurve& anchor : kShapes)
        for (double c : {-0.3, 0.25, 1.1}) {
            const BjontegaardResult r = JodGainAtEqualRays(anchor, HigherJod(anchor, c));
            INFO("c = " << c << ": " << r.reason);
            REQUIRE(r.Ok());
            CHECK(Near(r.value, c));
            CHECK(Near(r.from, std::log(anchor.front().rays)));
            CHECK(Near(r.to, std::log(anchor.back().rays)));
        }
    // JOD linear in ln rays, sampled at other budgets over a partial overlap.
    const auto jodLinear = [](const std::vector<double>& rays, double offset) {
        RateQualityCurve out;
        for (double r : rays) out.push_back({r, 4.0 + 1.3 * std::log(r) + offset});
        return out;
    };
    const BjontegaardResult r =
        JodGainAtEqualRays(jodLinear({1, 2, 4, 8}, 0.0), jodLinear({3, 5, 6, 12, 30}, 0.4));
    REQUIRE(r.Ok());
    CHECK(Near(r.value, 0.4));
    CHECK(Near(r.from, std::log(3.0)));
    CHECK(Near(r.to, std::log(8.0)));
}

TEST_CASE("identical curves save nothing and gain nothing, in any point order", "[rate_quality]") {
    for (const RateQualityCurve& anchor : kShapes) {
        const RateQualityCurve reversed(anchor.rbegin(), anchor.rend());
        CHECK(RaysSavedAtEqualJod(anchor, reversed).value == 1.0);
        CHECK(JodGainAtEqualRays(anchor, reversed).value == 0.0);
        CHECK(RaysSavedAtEqualJod(anchor, anchor, RateQualityFit::kCubic).value == 1.0);
    }
}

TEST_CASE("curves that do not overlap give no result, naming the ranges", "[rate_quality]") {
    const RateQualityCurve low = {{1, 3.0}, {2, 4.0}, {4, 5.0}};
    const RateQualityCurve high = {{8, 6.0}, {16, 7.0}};
    const RateQualityCurve touching = {{8, 5.0}, {16, 7.0}};  // meets `low` in one JOD only
    for (const RateQualityCurve* test : {&high, &touching}) {
        const BjontegaardResult r = RaysSavedAtEqualJod(low, *test);
        CHECK_FALSE(r.Ok());
        CHECK(std::isnan(r.value));
        CHECK(Contains(r.reason, "JOD do not overlap: anchor [3, 5]"));
    }
    const BjontegaardResult rays = JodGainAtEqualRays(low, high);
    CHECK_FALSE(rays.Ok());
    CHECK(Contains(rays.reason, "rays do not overlap: anchor [1, 4], test [8, 16]"));
}

TEST_CASE("a curve that is not a rate-quality curve gives no result, naming the point", "[rate_quality]") {
    const RateQualityCurve good = {{1, 5.0}, {2, 6.0}, {4, 7.0}};
    const double nan = std::nan("");
    const std::vector<std::pair<RateQualityCurve, std::string>> bad = {
        {{{1, 5.0}}, "test curve: 1 point(s); the fit needs at least 2"},
        {{}, "test curve: 0 point(s)"},
        {{{1, 5.0}, {2, nan}}, "test curve: point 1 is not finite"},
        {{{1, 5.0}, {INFINITY, 6.0}}, "test curve: point 1 is not finite"},
        {{{0, 5.0}, {2, 6.0}}, "test curve: point 0 has rays 0; rays must be > 0"},
        {{{-1, 5.0}, {2, 6.0}}, "rays must be > 0"},
        {{{1, 5.0}, {2, 6.0}, {2, 6.5}}, "test curve: two points at 2 rays"},
        {{{1, 5.0}, {2, 6.0}, {4, 6.0}},
         "test curve: not monotone: JOD 6 at 4 rays is not above JOD 6 at 2 rays"},
        {{{4, 5.5}, {1, 5.0}, {2, 6.0}},
         "test curve: not monotone: JOD 5.5 at 4 rays is not above JOD 6 at 2 rays"},
    };
    for (const auto& [curve, reason] : bad)
        for (RateQualityDelta delta : {RateQualityDelta::kRaysSaved, RateQualityDelta::kJodGain}) {
            const BjontegaardResult r = BjontegaardDelta(good, curve, delta);
            INFO(r.reason);
            CHECK_FALSE(r.Ok());
            CHECK(std::isnan(r.value));
            CHECK(Contains(r.reason, reason));
        }
    // The anchor is checked and named too; the cubic needs four points.
    CHECK(Contains(RaysSavedAtEqualJod(bad[0].first, good).reason, "anchor curve: 1 point(s)"));
    CHECK(Contains(RaysSavedAtEqualJod(good, good, RateQualityFit::kCubic).reason,
                   "anchor curve: 3 point(s); the fit needs at least 4"));
}

TEST_CASE("PCHIP has the Fritsch-Carlson slopes, reproduces the knots and keeps monotone data monotone",
          "[rate_quality]") {
    // Hand-computed: h = (1, 2), secants (1, 2). Interior: w1 = 2·2 + 1 = 5, w2 = 2 + 2·1 = 4,
    // (5 + 4)/(5/1 + 4/2) = 9/7. Ends: ((2·1 + 2)·1 − 1·2)/3 = 2/3 and ((2·2 + 1)·2 − 2·1)/3 = 8/3.
    const Pchip rising({0.0, 1.0, 3.0}, {0.0, 1.0, 5.0});
    CHECK(rising.Slopes()[0] == Approx(2.0 / 3.0));
    CHECK(rising.Slopes()[1] == Approx(9.0 / 7.0));
    CHECK(rising.Slopes()[2] == Approx(8.0 / 3.0));
    // Secants (1, −11) change sign: the interior slope is 0, the first end's three-point estimate
    // (3·1 + 11)/2 = 7 is limited to 3·1, the last end's (3·(−11) − 1)/2 = −17 is kept.
    const Pchip peak({0.0, 1.0, 2.0}, {0.0, 1.0, -10.0});
    CHECK(peak.Slopes()[0] == Approx(3.0));
    CHECK(peak.Slopes()[1] == 0.0);
    CHECK(peak.Slopes()[2] == Approx(-17.0));
    // Two knots: the line.
    const Pchip line({1.0, 3.0}, {2.0, 6.0});
    CHECK(line.Slopes() == std::vector<double>{2.0, 2.0});
    CHECK(line(2.0) == Approx(4.0));

    // A steep step with flat parts, where an unconstrained cubic spline overshoots.
    const std::vector<double> x = {0.0, 1.0, 2.0, 2.5, 3.0, 5.0, 6.0};
    const std::vector<double> y = {0.0, 0.0, 0.1, 4.0, 4.1, 4.1, 4.2};
    const Pchip step(x, y);
    for (size_t i = 0; i < x.size(); ++i) CHECK(step(x[i]) == Approx(y[i]).margin(1e-12));
    double previous = step(x.front());
    for (int i = 1; i <= 6000; ++i) {
        const double v = step(6.0 * i / 6000.0);
        REQUIRE(v >= previous - 1e-12);
        previous = v;
    }
    CHECK(previous == Approx(4.2));
    // The integral is the exact one of the cubic pieces: a fine midpoint sum agrees.
    double sum = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) sum += step(0.5 + 4.0 * (i + 0.5) / n) * 4.0 / n;
    CHECK(step.Integral(0.5, 4.5) == Approx(sum).epsilon(1e-8));
    CHECK(line.Integral(1.0, 3.0) == Approx(8.0));
}

namespace {

// A sweep measured with `seeds` seeds: the base curve's JOD plus seed noise of half-width
// `noise` (uniform, a fixed stream per curve).
SeededRateQualityCurve Seeded(const RateQualityCurve& base, size_t seeds, double noise, uint64_t stream) {
    Pcg32 rng(7, stream);
    SeededRateQualityCurve out;
    for (const RateQualityPoint& p : base) {
        SeededRateQualityPoint q{p.rays, {}};
        for (size_t s = 0; s < seeds; ++s) q.jodPerSeed.push_back(p.jod + noise * (2.0 * rng.NextFloat() - 1.0));
        out.push_back(q);
    }
    return out;
}

double Width(const BjontegaardInterval& i) { return i.upper - i.lower; }

}  // namespace

TEST_CASE("the seed bootstrap interval holds the estimate and shrinks with the seed noise", "[rate_quality]") {
    const RateQualityCurve base = kShapes[0];
    const RateQualityCurve better = HigherJod(FewerRays(base, 1.5), 0.1);
    for (RateQualityDelta delta : {RateQualityDelta::kRaysSaved, RateQualityDelta::kJodGain}) {
        const auto interval = [&](double noise) {
            return BootstrapBjontegaardDelta(Seeded(base, 8, noise, 1), Seeded(better, 8, noise, 2), delta);
        };
        const BjontegaardInterval noisy = interval(0.2), quiet = interval(0.02);
        INFO(noisy.estimate.reason << noisy.intervalReason);
        REQUIRE(noisy.intervalReason.empty());
        REQUIRE(quiet.intervalReason.empty());
        CHECK(noisy.lower <= noisy.estimate.value);
        CHECK(noisy.estimate.value <= noisy.upper);
        CHECK(quiet.lower <= quiet.estimate.value);
        CHECK(quiet.estimate.value <= quiet.upper);
        CHECK(Width(noisy) > 0.0);
        CHECK(Width(quiet) < 0.2 * Width(noisy));
        // The estimate is the delta of the seed means; a fixed RNG seed gives the same interval.
        CHECK(Near(quiet.estimate.value, BjontegaardDelta(base, better, delta).value, 0.05));
        const BjontegaardInterval again = interval(0.2);
        CHECK(again.lower == noisy.lower);
        CHECK(again.upper == noisy.upper);
    }
}

TEST_CASE("equal seeds give a degenerate interval; seeds resampled in pairs cancel shared noise",
          "[rate_quality]") {
    const RateQualityCurve base = kShapes[1];
    const BjontegaardInterval equal = BootstrapBjontegaardDelta(
        Seeded(base, 5, 0.0, 1), Seeded(FewerRays(base, 2.0), 5, 0.0, 2), RateQualityDelta::kRaysSaved);
    REQUIRE(equal.intervalReason.empty());
    CHECK(Near(equal.estimate.value, 2.0));
    CHECK(equal.lower == equal.estimate.value);
    CHECK(equal.upper == equal.estimate.value);

    // The test curve is the anchor's own per-seed JOD at half the rays: every paired resample
    // moves both curves alike and still saves exactly 2.
    const SeededRateQualityCurve anchor = Seeded(kShapes[0], 6, 0.15, 3);
    SeededRateQualityCurve test = anchor;
    for (SeededRateQualityPoint& p : test) p.rays /= 2.0;
    const BjontegaardInterval paired = BootstrapBjontegaardDelta(anchor, test, RateQualityDelta::kRaysSaved);
    REQUIRE(paired.intervalReason.empty());
    CHECK(Near(paired.lower, 2.0));
    CHECK(Near(paired.upper, 2.0));
}

TEST_CASE("the bootstrap refuses mismatched or non-finite seeds and curves resampling makes non-monotone",
          "[rate_quality]") {
    SeededRateQualityCurve anchor = Seeded(kShapes[0], 4, 0.05, 1);
    const SeededRateQualityCurve test = Seeded(FewerRays(kShapes[0], 2.0), 4, 0.05, 2);
    anchor[2].jodPerSeed.pop_back();
    const BjontegaardInterval mismatched = BootstrapBjontegaardDelta(anchor, test, RateQualityDelta::kRaysSaved);
    CHECK(Contains(mismatched.estimate.reason, "anchor curve: point 2 has 3 seeds, the first point 4"));
    CHECK(std::isnan(mismatched.lower));
    SeededRateQualityCurve nonFinite = test;
    nonFinite[1].jodPerSeed[3] = std::nan("");
    const BjontegaardInterval nan = BootstrapBjontegaardDelta(test, nonFinite, RateQualityDelta::kJodGain);
    CHECK(Contains(nan.estimate.reason, "test curve: point 1 is not finite"));
    CHECK(nan.intervalReason == "no estimate");

    // Seed 1 swaps two points' order in JOD: the mean is monotone, a quarter of the resamples
    // (seed 1 drawn twice) are not, more than the 2.5 % the interval's tail can lose.
    const SeededRateQualityCurve swapped = {
        {1.0, {5.0, 5.0}}, {2.0, {6.0, 7.0}}, {4.0, {7.5, 6.5}}, {8.0, {8.0, 8.0}}};
    const BjontegaardInterval noInterval =
        BootstrapBjontegaardDelta(swapped, swapped, RateQualityDelta::kRaysSaved);
    CHECK(noInterval.estimate.Ok());
    CHECK(noInterval.estimate.value == 1.0);
    CHECK(noInterval.failedReplicates > 300);
    CHECK(std::isnan(noInterval.lower));
    CHECK(Contains(noInterval.intervalReason,
                   "bootstrap resamples give no result (more than 2.5 %), e.g. anchor curve: not monotone"));
}

TEST_CASE("rays saved at a point: k on a curve k times cheaper, the log-linear closed form between knots, "
          "nothing outside the anchor's range",
          "[rate_quality]") {
    // At the anchor's own knots every fit passes through them: a point with k× fewer rays saves k.
    for (const RateQualityCurve& anchor : kShapes)
        for (double k : {0.5, 2.0, 3.3})
            for (const RateQualityPoint& p : FewerRays(anchor, k)) {
                const BjontegaardResult r = RaysSavedAtPoint(anchor, p);
                INFO("k = " << k << " at JOD " << p.jod << ": " << r.reason);
                REQUIRE(r.Ok());
                CHECK(Near(r.value, k));
                CHECK(r.from == p.jod);
            }
    // Between knots on ln R = a + bQ (PCHIP and the cubic reproduce a line): the anchor needs
    // exp(a + bQ) rays for the point's JOD Q.
    const RateQualityCurve anchor = LogLinear({3.0, 4.0, 6.0, 7.0, 9.0}, 0.2, 0.45);
    for (RateQualityFit fit : {RateQualityFit::kPchip, RateQualityFit::kCubic})
        for (double q : {3.0, 4.6, 8.25, 9.0}) {
            const BjontegaardResult r = RaysSavedAtPoint(anchor, {1.5, q}, fit);
            REQUIRE(r.Ok());
            CHECK(Near(r.value, std::exp(0.2 + 0.45 * q) / 1.5));
        }
    // Outside the anchor's JOD range nothing is extrapolated; bad input names itself.
    const BjontegaardResult above = RaysSavedAtPoint(anchor, {1.0, 9.5});
    CHECK(!above.Ok());
    CHECK(Contains(above.reason, "the point's JOD 9.5 lies outside the anchor's [3, 9]"));
    CHECK(Contains(RaysSavedAtPoint(anchor, {0.0, 5.0}).reason, "test curve: point 0 has rays 0"));
    CHECK(Contains(RaysSavedAtPoint({{1.0, 5.0}, {2.0, 5.0}}, {1.0, 5.0}).reason, "anchor curve: not monotone"));

    // With seeds: the anchor's own per-seed JOD at a third of the rays saves 3 in every paired
    // resample; a point with other seeds than the anchor's has no estimate.
    const SeededRateQualityCurve seeded = Seeded(kShapes[0], 5, 0.1, 7);
    SeededRateQualityPoint point = seeded[2];
    point.rays /= 3.0;
    const BjontegaardInterval paired = BootstrapRaysSavedAtPoint(seeded, point);
    REQUIRE(paired.intervalReason.empty());
    CHECK(Near(paired.estimate.value, 3.0));
    CHECK(Near(paired.lower, 3.0));
    CHECK(Near(paired.upper, 3.0));
    point.jodPerSeed.pop_back();
    CHECK(Contains(BootstrapRaysSavedAtPoint(seeded, point).estimate.reason, "test curve: point 0 has 4 seeds"));
}
