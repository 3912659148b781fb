#include "metrics/rate_quality.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "core/check.h"
#include "core/rng.h"
#include "metrics/statistics.h"

namespace fovrt {

namespace {

// ∫_u^v f for a cubic f: the two-point Gauss–Legendre rule is exact to degree 3.
template <typename F>
double GaussCubic(const F& f, double u, double v) {
    const double mid = 0.5 * (u + v), half = 0.5 * (v - u);
    const double r = half / std::sqrt(3.0);
    return half * (f(mid - r) + f(mid + r));
}

// The least-squares cubic polynomial through (x_i, y_i), in u = (x − center) / scale so that the
// normal equations stay well conditioned for JOD around 8 or ln rays around 3.
class CubicFit {
public:
    CubicFit(const std::vector<double>& x, const std::vector<double>& y) {
        center_ = 0.5 * (x.front() + x.back());
        scale_ = 0.5 * (x.back() - x.front());
        std::array<std::array<double, 5>, 4> a{};  // the normal equations, right-hand side last
        for (size_t i = 0; i < x.size(); ++i) {
            const double u = (x[i] - center_) / scale_;
            const std::array<double, 4> p = {1.0, u, u * u, u * u * u};
            for (int r = 0; r < 4; ++r) {
                for (int c = 0; c < 4; ++c) a[r][c] += p[r] * p[c];
                a[r][4] += p[r] * y[i];
            }
        }
        // Gaussian elimination with partial pivoting; distinct x (at least 4) make it regular.
        for (int c = 0; c < 4; ++c) {
            int pivot = c;
            for (int r = c + 1; r < 4; ++r)
                if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
            std::swap(a[c], a[pivot]);
            for (int r = c + 1; r < 4; ++r) {
                const double f = a[r][c] / a[c][c];
                for (int k = c; k < 5; ++k) a[r][k] -= f * a[c][k];
            }
        }
        for (int r = 3; r >= 0; --r) {
            double s = a[r][4];
            for (int k = r + 1; k < 4; ++k) s -= a[r][k] * coefficients_[k];
            coefficients_[r] = s / a[r][r];
        }
    }
    double operator()(double x) const {
        const double u = (x - center_) / scale_;
        return coefficients_[0] + u * (coefficients_[1] + u * (coefficients_[2] + u * coefficients_[3]));
    }
    double Integral(double a, double b) const { return GaussCubic(*this, a, b); }

private:
    double center_ = 0.0, scale_ = 1.0;
    std::array<double, 4> coefficients_{};
};

double FitIntegral(const std::vector<double>& x, const std::vector<double>& y, RateQualityFit fit, double a,
                   double b) {
    if (fit == RateQualityFit::kCubic) return CubicFit(x, y).Integral(a, b);
    return Pchip(x, y).Integral(a, b);
}

double FitValue(const std::vector<double>& x, const std::vector<double>& y, RateQualityFit fit, double at) {
    if (fit == RateQualityFit::kCubic) return CubicFit(x, y)(at);
    return Pchip(x, y)(at);
}

// The curve sorted by rays, or the reason it is not a rate–quality curve.
std::string CheckCurve(const RateQualityCurve& curve, const char* name, const std::string& quality, size_t minPoints,
                       RateQualityCurve& sorted) {
    if (curve.size() < minPoints)
        return fmt::format("{} curve: {} point(s); the fit needs at least {}", name, curve.size(), minPoints);
    for (size_t i = 0; i < curve.size(); ++i) {
        const RateQualityPoint& p = curve[i];
        if (!std::isfinite(p.rays) || !std::isfinite(p.jod))
            return fmt::format("{} curve: point {} is not finite (rays {}, {} {})", name, i, p.rays, quality, p.jod);
        if (p.rays <= 0.0) return fmt::format("{} curve: point {} has rays {}; rays must be > 0", name, i, p.rays);
    }
    sorted = curve;
    std::sort(sorted.begin(), sorted.end(),
              [](const RateQualityPoint& a, const RateQualityPoint& b) { return a.rays < b.rays; });
    for (size_t i = 1; i < sorted.size(); ++i) {
        const RateQualityPoint &lo = sorted[i - 1], &hi = sorted[i];
        if (hi.rays == lo.rays) return fmt::format("{} curve: two points at {} rays", name, hi.rays);
        if (!(hi.jod > lo.jod))
            return fmt::format(
                "{0} curve: not monotone: {1} {2} at {3} rays is not above {1} {4} at {5} rays (a rate-quality "
                "curve needs {1} strictly increasing with rays)",
                name, quality, hi.jod, hi.rays, lo.jod, lo.rays);
    }
    return {};
}

// Unzips a sorted curve into the fit's abscissa and ordinate.
void Axes(const RateQualityCurve& sorted, RateQualityDelta delta, std::vector<double>& x, std::vector<double>& y) {
    x.clear(), y.clear();
    for (const RateQualityPoint& p : sorted) {
        const double logRays = std::log(p.rays);
        x.push_back(delta == RateQualityDelta::kRaysSaved ? p.jod : logRays);
        y.push_back(delta == RateQualityDelta::kRaysSaved ? logRays : p.jod);
    }
}

// The per-point JOD averaged over the seeds `draw` picks (with repeats), in the draw's order.
RateQualityCurve MeanCurve(const SeededRateQualityCurve& curve, const std::vector<uint32_t>& draw) {
    RateQualityCurve mean;
    mean.reserve(curve.size());
    for (const SeededRateQualityPoint& p : curve) {
        double sum = 0.0;
        for (uint32_t s : draw) sum += p.jodPerSeed[s];
        mean.push_back({p.rays, sum / double(draw.size())});
    }
    return mean;
}

// The number of seeds every point of both curves shares, or the reason there is none.
std::string SharedSeedCount(const SeededRateQualityCurve& anchor, const SeededRateQualityCurve& test,
                            size_t& seeds) {
    seeds = 0;
    for (const auto& [name, curve] : {std::pair{"anchor", &anchor}, std::pair{"test", &test}})
        for (size_t i = 0; i < curve->size(); ++i) {
            const size_t n = (*curve)[i].jodPerSeed.size();
            if (n == 0) return fmt::format("{} curve: point {} has no seeds", name, i);
            if (seeds == 0) seeds = n;
            if (n != seeds)
                return fmt::format(
                    "{} curve: point {} has {} seeds, the first point {}; every point needs the same seeds", name,
                    i, n, seeds);
        }
    return {};
}

}  // namespace

Pchip::Pchip(std::vector<double> x, std::vector<double> y) : x_(std::move(x)), y_(std::move(y)) {
    FOVRT_CHECK_OP(x_.size(), ==, y_.size());
    FOVRT_CHECK_OP(x_.size(), >=, size_t(2));
    const size_t n = x_.size();
    std::vector<double> h(n - 1), secant(n - 1);
    for (size_t k = 0; k + 1 < n; ++k) {
        FOVRT_CHECK_OP(x_[k], <, x_[k + 1]);
        h[k] = x_[k + 1] - x_[k];
        secant[k] = (y_[k + 1] - y_[k]) / h[k];
    }
    slopes_.assign(n, secant[0]);
    if (n == 2) return;
    for (size_t k = 1; k + 1 < n; ++k) {
        if (secant[k - 1] * secant[k] <= 0.0) {
            slopes_[k] = 0.0;  // a local extremum (or a flat piece) stays one
            continue;
        }
        const double w1 = 2.0 * h[k] + h[k - 1], w2 = h[k] + 2.0 * h[k - 1];
        slopes_[k] = (w1 + w2) / (w1 / secant[k - 1] + w2 / secant[k]);
    }
    // The end slope: three-point estimate, kept in the sign of the end secant and within 3× it.
    const auto end = [](double h0, double h1, double m0, double m1) {
        const double d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1);
        if (std::signbit(d) != std::signbit(m0) || m0 == 0.0) return 0.0;
        if (std::signbit(m0) != std::signbit(m1) && std::abs(d) > 3.0 * std::abs(m0)) return 3.0 * m0;
        return d;
    };
    slopes_[0] = end(h[0], h[1], secant[0], secant[1]);
    slopes_[n - 1] = end(h[n - 2], h[n - 3], secant[n - 2], secant[n - 3]);
}

size_t Pchip::Segment(double x) const {
    FOVRT_CHECK(x >= x_.front() && x <= x_.back());
    const size_t upper = size_t(std::upper_bound(x_.begin(), x_.end(), x) - x_.begin());
    return std::min(upper, x_.size() - 1) - 1;
}

double Pchip::operator()(double x) const {
    const size_t i = Segment(x);
    const double h = x_[i + 1] - x_[i], t = (x - x_[i]) / h;
    const double t2 = t * t, t3 = t2 * t;
    return (2.0 * t3 - 3.0 * t2 + 1.0) * y_[i] + (t3 - 2.0 * t2 + t) * h * slopes_[i] +
           (-2.0 * t3 + 3.0 * t2) * y_[i + 1] + (t3 - t2) * h * slopes_[i + 1];
}

double Pchip::Integral(double a, double b) const {
    FOVRT_CHECK_OP(a, <=, b);
    double sum = 0.0;
    for (size_t i = Segment(a); i + 1 < x_.size() && x_[i] < b; ++i) {
        const double u = std::max(a, x_[i]), v = std::min(b, x_[i + 1]);
        if (v > u) sum += GaussCubic(*this, u, v);
    }
    return sum;
}

BjontegaardResult BjontegaardDelta(const RateQualityCurve& anchor, const RateQualityCurve& test,
                                   RateQualityDelta delta, RateQualityFit fit, const std::string& quality) {
    BjontegaardResult result;
    const size_t minPoints = fit == RateQualityFit::kCubic ? 4 : 2;
    RateQualityCurve sortedAnchor, sortedTest;
    result.reason = CheckCurve(anchor, "anchor", quality, minPoints, sortedAnchor);
    if (result.reason.empty()) result.reason = CheckCurve(test, "test", quality, minPoints, sortedTest);
    if (!result.Ok()) return result;

    std::vector<double> xa, ya, xt, yt;
    Axes(sortedAnchor, delta, xa, ya);
    Axes(sortedTest, delta, xt, yt);
    const double from = std::max(xa.front(), xt.front()), to = std::min(xa.back(), xt.back());
    if (!(to > from)) {
        // The ranges as measured (rays, not ln rays).
        const bool jod = delta == RateQualityDelta::kRaysSaved;
        const auto range = [jod](const RateQualityCurve& c) {
            return jod ? fmt::format("[{:.4g}, {:.4g}]", c.front().jod, c.back().jod)
                       : fmt::format("[{:.4g}, {:.4g}]", c.front().rays, c.back().rays);
        };
        result.reason = fmt::format("the curves' {} do not overlap: anchor {}, test {}", jod ? quality : "rays",
                                    range(sortedAnchor), range(sortedTest));
        return result;
    }
    const double meanDifference =
        (FitIntegral(xt, yt, fit, from, to) - FitIntegral(xa, ya, fit, from, to)) / (to - from);
    result.value = delta == RateQualityDelta::kRaysSaved ? std::exp(-meanDifference) : meanDifference;
    result.from = from;
    result.to = to;
    return result;
}

namespace {

// The paired seed bootstrap of `estimate(draw)`, a result from the seed means over the drawn seed
// indices (with repeats): the estimate on all seeds, then `options.resamples` replicates.
template <typename Estimate>
BjontegaardInterval BootstrapOverSeeds(size_t seeds, const Estimate& estimate, const BjontegaardIntervalOptions& options) {
    FOVRT_CHECK_OP(options.resamples, >=, 1);
    FOVRT_CHECK(options.confidence > 0.0 && options.confidence < 1.0);
    BjontegaardInterval interval;
    std::vector<uint32_t> draw(seeds);
    for (size_t s = 0; s < seeds; ++s) draw[s] = uint32_t(s);
    interval.estimate = estimate(draw);
    if (!interval.estimate.Ok()) {
        interval.intervalReason = "no estimate";
        return interval;
    }

    Pcg32 rng(options.rngSeed);
    std::vector<double> replicates;
    replicates.reserve(size_t(options.resamples));
    std::string firstFailure;
    for (int r = 0; r < options.resamples; ++r) {
        for (uint32_t& s : draw) s = rng.NextBounded(uint32_t(seeds));
        const BjontegaardResult replicate = estimate(draw);
        if (replicate.Ok()) {
            replicates.push_back(replicate.value);
        } else {
            if (firstFailure.empty()) firstFailure = replicate.reason;
            ++interval.failedReplicates;
        }
    }
    // A dropped replicate might have been in either tail: more than one tail's worth of them
    // could move a bound anywhere.
    const double tail = 0.5 * (1.0 - options.confidence);
    if (double(interval.failedReplicates) > tail * double(options.resamples)) {
        interval.intervalReason =
            fmt::format("{} of {} bootstrap resamples give no result (more than {:g} %), e.g. {}",
                        interval.failedReplicates, options.resamples, 100.0 * tail, firstFailure);
        return interval;
    }
    interval.lower = Quantile(replicates, tail);
    interval.upper = Quantile(replicates, 1.0 - tail);
    return interval;
}

BjontegaardInterval NoSeeds(std::string reason) {
    BjontegaardInterval interval;
    interval.estimate.reason = std::move(reason);
    interval.intervalReason = "no estimate";
    return interval;
}

}  // namespace

BjontegaardInterval BootstrapBjontegaardDelta(const SeededRateQualityCurve& anchor,
                                              const SeededRateQualityCurve& test, RateQualityDelta delta,
                                              const BjontegaardIntervalOptions& options) {
    size_t seeds = 0;
    if (std::string reason = SharedSeedCount(anchor, test, seeds); !reason.empty()) return NoSeeds(reason);
    return BootstrapOverSeeds(
        seeds,
        [&](const std::vector<uint32_t>& draw) {
            return BjontegaardDelta(MeanCurve(anchor, draw), MeanCurve(test, draw), delta, options.fit, options.quality);
        },
        options);
}

BjontegaardResult RaysSavedAtPoint(const RateQualityCurve& anchor, const RateQualityPoint& test, RateQualityFit fit,
                                   const std::string& quality) {
    BjontegaardResult result;
    RateQualityCurve sortedAnchor, sortedTest;
    result.reason = CheckCurve(anchor, "anchor", quality, fit == RateQualityFit::kCubic ? 4 : 2, sortedAnchor);
    if (result.reason.empty()) result.reason = CheckCurve({test}, "test", quality, 1, sortedTest);
    if (!result.Ok()) return result;
    std::vector<double> q, logRays;
    Axes(sortedAnchor, RateQualityDelta::kRaysSaved, q, logRays);
    if (test.jod < q.front() || test.jod > q.back()) {
        result.reason = fmt::format("the point's {} {:.6g} lies outside the anchor's [{:.6g}, {:.6g}]", quality, test.jod,
                                    q.front(), q.back());
        return result;
    }
    result.value = std::exp(FitValue(q, logRays, fit, test.jod)) / test.rays;
    result.from = result.to = test.jod;
    return result;
}

BjontegaardInterval BootstrapRaysSavedAtPoint(const SeededRateQualityCurve& anchor, const SeededRateQualityPoint& test,
                                              const BjontegaardIntervalOptions& options) {
    size_t seeds = 0;
    if (std::string reason = SharedSeedCount(anchor, {test}, seeds); !reason.empty()) return NoSeeds(reason);
    return BootstrapOverSeeds(
        seeds,
        [&](const std::vector<uint32_t>& draw) {
            return RaysSavedAtPoint(MeanCurve(anchor, draw), MeanCurve({test}, draw).front(), options.fit,
                                    options.quality);
        },
        options);
}

}  // namespace fovrt
