// Rate–quality curves of a budget sweep and what one design saves against another at equal
// perceived quality (Bjøntegaard 2001, VCEG-M33). A curve is one (scene, denoiser, design)'s
// points (rays, JOD): rays = measured traced path samples per pixel, JOD = FovVideoVDP quality.
// Pure functions of their inputs: no I/O, a fixed RNG seed for the interval.
//
// Method (docs/experiments.md, "Rate–quality curves and rays saved"):
//   - Rays saved at equal JOD: ln R is fitted as a function of Q on each curve, both fits are
//     integrated over the JOD interval both curves cover, and the mean difference
//     Δ = mean(ln R_anchor − ln R_test) gives the ratio exp(Δ): the anchor's rays over the test's
//     at equal quality (> 1: the test design needs fewer rays).
//   - JOD gain at equal rays, the dual: Q fitted as a function of ln R, mean(Q_test − Q_anchor)
//     over the ln R interval both cover.
//   - The fit is a monotone piecewise cubic (PCHIP: Fritsch & Carlson 1980, the slopes as Moler's
//     pchip and SciPy's PchipInterpolator compute them), as current video-coding test conditions
//     use; the classic least-squares cubic polynomial of VCEG-M33 is an option.
//   - A curve must be a rate–quality curve: at least 2 points (4 for the cubic), finite values,
//     rays > 0, and, sorted by rays, both rays and JOD strictly increasing. Anything else (equal
//     rays, equal JOD, a point with more rays and no more JOD) is no result, with the reason:
//     such a curve has no single "rays needed for a JOD", and the sweep needs more seeds or
//     budgets further apart. Curves whose intervals do not overlap (or touch in one point) give
//     no result either.
//   - Interval: a paired bootstrap over seeds (the unit of independent noise): the seed indices
//     are resampled with replacement, the same draw for every point of both curves, the per-point
//     JOD averaged over the drawn seeds, both curves refitted and the delta recomputed; the
//     interval is the percentile interval of the replicates. Replicates without a result (a
//     resample that makes a curve non-monotone) are dropped and counted; when more than the
//     interval's one-tail mass ((1 − confidence)/2) of them fail there is no interval.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace fovrt {

// One point of a budget sweep.
struct RateQualityPoint {
    double rays = 0.0;  // measured traced path samples per pixel, > 0
    double jod = 0.0;   // FovVideoVDP quality
};
using RateQualityCurve = std::vector<RateQualityPoint>;

enum class RateQualityFit {
    kPchip,  // monotone piecewise cubic through the points (the default)
    kCubic,  // least-squares cubic polynomial (VCEG-M33), at least 4 points
};

// What a delta measures.
enum class RateQualityDelta {
    kRaysSaved,  // anchor rays / test rays at equal JOD, a ratio
    kJodGain,    // test JOD − anchor JOD at equal rays, in JOD
};

struct BjontegaardResult {
    double value = std::numeric_limits<double>::quiet_NaN();
    // The overlap integrated over: JOD for rays saved, ln rays for JOD gain.
    double from = std::numeric_limits<double>::quiet_NaN();
    double to = std::numeric_limits<double>::quiet_NaN();
    std::string reason;  // why there is no value; empty when there is one
    bool Ok() const { return reason.empty(); }
};

// `quality` names the ordinate in the reasons (the sweep also fits −ln foveal relMSE as a quality).
BjontegaardResult BjontegaardDelta(const RateQualityCurve& anchor, const RateQualityCurve& test,
                                   RateQualityDelta delta, RateQualityFit fit = RateQualityFit::kPchip,
                                   const std::string& quality = "JOD");
inline BjontegaardResult RaysSavedAtEqualJod(const RateQualityCurve& anchor, const RateQualityCurve& test,
                                             RateQualityFit fit = RateQualityFit::kPchip) {
    return BjontegaardDelta(anchor, test, RateQualityDelta::kRaysSaved, fit);
}
inline BjontegaardResult JodGainAtEqualRays(const RateQualityCurve& anchor, const RateQualityCurve& test,
                                            RateQualityFit fit = RateQualityFit::kPchip) {
    return BjontegaardDelta(anchor, test, RateQualityDelta::kJodGain, fit);
}

// A point of a sweep with its JOD per seed; every point of both curves has the same seeds, in the
// same order.
struct SeededRateQualityPoint {
    double rays = 0.0;
    std::vector<double> jodPerSeed;
};
using SeededRateQualityCurve = std::vector<SeededRateQualityPoint>;

struct BjontegaardIntervalOptions {
    RateQualityFit fit = RateQualityFit::kPchip;
    int resamples = 2000;
    double confidence = 0.95;
    uint64_t rngSeed = 0x5eedb007;  // fixed: reports are reproducible
    std::string quality = "JOD";     // the ordinate's name in the reasons
};

struct BjontegaardInterval {
    BjontegaardResult estimate;  // on the JOD averaged over all seeds
    double lower = std::numeric_limits<double>::quiet_NaN();
    double upper = std::numeric_limits<double>::quiet_NaN();
    int failedReplicates = 0;    // replicates without a result, dropped
    std::string intervalReason;  // why there is no interval; empty when lower/upper hold it
};
BjontegaardInterval BootstrapBjontegaardDelta(const SeededRateQualityCurve& anchor,
                                              const SeededRateQualityCurve& test, RateQualityDelta delta,
                                              const BjontegaardIntervalOptions& options = {});

// Rays saved at one point of the test curve: the anchor's rays at the point's quality (its fit of
// ln R over Q) over the point's rays; above 1 the point needs fewer. Where a single delta averages
// over the whole overlap, this says how the saving changes with the budget. No value when the
// anchor is not a rate–quality curve or the point's quality lies outside the anchor's range
// (nothing is extrapolated). `from` and `to` are the point's quality.
BjontegaardResult RaysSavedAtPoint(const RateQualityCurve& anchor, const RateQualityPoint& test,
                                   RateQualityFit fit = RateQualityFit::kPchip, const std::string& quality = "JOD");
// The same on the seed means, with the paired seed bootstrap (the point has the anchor's seeds).
BjontegaardInterval BootstrapRaysSavedAtPoint(const SeededRateQualityCurve& anchor, const SeededRateQualityPoint& test,
                                              const BjontegaardIntervalOptions& options = {});

// The monotone piecewise cubic Hermite interpolant (PCHIP) through (x_i, y_i), x strictly
// increasing. Slopes (Fritsch & Carlson 1980; weights of Fritsch & Butland 1984): 0 at an
// interior knot where the secants change sign or one is 0, else the weighted harmonic mean
// (w1 + w2) / (w1/δ_{k−1} + w2/δ_k), w1 = 2h_k + h_{k−1}, w2 = h_k + 2h_{k−1}; at the ends the
// three-point estimate ((2h_0 + h_1)δ_0 − h_0δ_1)/(h_0 + h_1), set to 0 when its sign differs
// from δ_0's and to 3δ_0 when the secants change sign and it exceeds 3|δ_0|; two knots: the line.
// Monotone data gives a monotone interpolant.
class Pchip {
public:
    Pchip(std::vector<double> x, std::vector<double> y);
    double operator()(double x) const;  // x within [x_0, x_{n−1}]
    // ∫_a^b, [a, b] within the knots (exact: two-point Gauss per piece of cubic).
    double Integral(double a, double b) const;
    const std::vector<double>& Slopes() const { return slopes_; }

private:
    size_t Segment(double x) const;
    std::vector<double> x_, y_, slopes_;
};

}  // namespace fovrt
