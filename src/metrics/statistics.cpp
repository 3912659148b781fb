#include "metrics/statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/check.h"
#include "core/rng.h"

namespace fovrt {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Autocovariance at lags 0..maxLag, pooled: Σ over sequences of Σ_t e_t e_{t+k} / Σ n, with each
// sequence demeaned on its own (a seed's offset is not autocorrelation).
std::vector<double> PooledAutocovariance(const std::vector<std::vector<double>>& sequences, int maxLag) {
    std::vector<double> acv(size_t(maxLag) + 1, 0.0);
    size_t total = 0;
    for (const std::vector<double>& s : sequences) {
        if (s.empty()) continue;
        const double mean = std::accumulate(s.begin(), s.end(), 0.0) / double(s.size());
        for (int k = 0; k <= maxLag; ++k)
            for (size_t t = 0; t + size_t(k) < s.size(); ++t) acv[size_t(k)] += (s[t] - mean) * (s[t + size_t(k)] - mean);
        total += s.size();
    }
    if (total > 0)
        for (double& v : acv) v /= double(total);
    return acv;
}

}  // namespace

Spread Summarize(const std::vector<double>& values) {
    std::vector<double> finite;
    for (double v : values)
        if (!std::isnan(v)) finite.push_back(v);
    Spread s;
    s.count = finite.size();
    if (finite.empty()) return {kNaN, kNaN, kNaN, 0};
    double sum = 0.0, logSum = 0.0;
    bool positive = true;
    for (double v : finite) {
        sum += v;
        if (v > 0.0) logSum += std::log(v);
        else positive = false;
    }
    s.mean = sum / double(finite.size());
    s.median = Quantile(finite, 0.5);
    s.geometricMean = positive ? std::exp(logSum / double(finite.size())) : kNaN;
    return s;
}

double Quantile(std::vector<double> values, double q) {
    if (values.empty()) return kNaN;
    std::sort(values.begin(), values.end());
    const double h = std::clamp(q, 0.0, 1.0) * double(values.size() - 1);
    const size_t lo = size_t(std::floor(h));
    const size_t hi = std::min(lo + 1, values.size() - 1);
    return values[lo] + (h - double(lo)) * (values[hi] - values[lo]);
}

int AutomaticBlockLength(const std::vector<std::vector<double>>& sequences) {
    size_t total = 0, count = 0, shortest = std::numeric_limits<size_t>::max();
    for (const auto& s : sequences)
        if (!s.empty()) total += s.size(), ++count, shortest = std::min(shortest, s.size());
    if (count == 0 || shortest < 4) return 1;
    const double n = double(total) / double(count);  // the length one block bootstrap resamples
    const int kn = std::max(5, int(std::sqrt(std::log10(n))));
    const int mMax = std::min(int(std::ceil(std::sqrt(n))) + kn, int(shortest) - 1);
    const double bMax = std::ceil(std::min(3.0 * std::sqrt(n), n / 3.0));
    const std::vector<double> acv = PooledAutocovariance(sequences, mMax);
    if (!(acv[0] > 0.0)) return 1;
    // m̂: the first lag after which kn autocorrelations in a row are insignificant.
    const double critical = 2.0 * std::sqrt(std::log10(n) / n);
    int mHat = -1;
    for (int m = 0; m + kn <= mMax && mHat < 0; ++m) {
        bool quiet = true;
        for (int j = 1; j <= kn && quiet; ++j) quiet = std::abs(acv[size_t(m + j)] / acv[0]) < critical;
        if (quiet) mHat = m;
    }
    const int M = mHat < 0 ? mMax : std::min(2 * std::max(mHat, 1), mMax);
    // Flat-top lag window λ(t) = 1 for |t| ≤ 1/2, 2(1 − |t|) up to 1.
    double g = 0.0, longRun = acv[0];
    for (int k = 1; k <= M; ++k) {
        const double t = double(k) / double(M);
        const double lambda = t <= 0.5 ? 1.0 : 2.0 * (1.0 - t);
        g += 2.0 * lambda * double(k) * acv[size_t(k)];
        longRun += 2.0 * lambda * acv[size_t(k)];
    }
    const double dCircular = 4.0 / 3.0 * longRun * longRun;
    if (!(dCircular > 0.0)) return 1;
    const double b = std::cbrt(2.0 * g * g / dCircular) * std::cbrt(n);
    if (!std::isfinite(b)) return 1;
    return int(std::clamp(std::round(b), 1.0, std::max(1.0, bMax)));
}

std::vector<double> BlockBootstrapMeans(const std::vector<std::vector<double>>& sequences, int blockLength,
                                        int resamples, uint64_t rngSeed) {
    FOVRT_CHECK_OP(blockLength, >=, 1);
    FOVRT_CHECK_OP(resamples, >=, 1);
    size_t total = 0;
    for (const auto& s : sequences) total += s.size();
    std::vector<double> means;
    if (total == 0) return means;
    means.reserve(size_t(resamples));
    Pcg32 rng(rngSeed);
    for (int r = 0; r < resamples; ++r) {
        double sum = 0.0;
        for (const std::vector<double>& s : sequences) {
            const size_t n = s.size();
            if (n == 0) continue;
            const size_t b = std::min(size_t(blockLength), n);
            for (size_t filled = 0; filled < n;) {
                size_t start = rng.NextBounded(uint32_t(n));
                for (size_t i = 0; i < b && filled < n; ++i, ++filled) sum += s[(start + i) % n];
            }
        }
        means.push_back(sum / double(total));
    }
    return means;
}

PairedRatio ComparePaired(const std::vector<PairedSequence>& sequences, Better better,
                          const BootstrapOptions& options) {
    PairedRatio result;
    std::vector<std::vector<double>> logRatios;
    double logSum = 0.0, wins = 0.0;
    for (const PairedSequence& s : sequences) {
        FOVRT_CHECK_OP(s.baseline.size(), ==, s.variant.size());
        std::vector<double> d;
        for (size_t t = 0; t < s.baseline.size(); ++t) {
            const double b = s.baseline[t], v = s.variant[t];
            if (!(std::isfinite(b) && std::isfinite(v) && b > 0.0 && v > 0.0)) {
                ++result.dropped;
                continue;
            }
            // Below the metrics' float precision the two are the same: a tie, log ratio 0.
            const bool tie = std::abs(v - b) <= kTieTolerance * std::max(v, b);
            d.push_back(tie ? 0.0 : std::log(v / b));
            logSum += d.back();
            const bool win = better == Better::kLower ? v < b : v > b;
            wins += tie ? 0.5 : win ? 1.0 : 0.0;
        }
        result.pairs += d.size();
        if (!d.empty()) logRatios.push_back(std::move(d));
    }
    if (result.pairs == 0) {
        result.ratio = result.lower = result.upper = result.winRate = kNaN;
        return result;
    }
    result.ratio = std::exp(logSum / double(result.pairs));
    result.winRate = wins / double(result.pairs);
    result.blockLength = options.blockLength > 0 ? options.blockLength : AutomaticBlockLength(logRatios);
    std::vector<double> means =
        BlockBootstrapMeans(logRatios, result.blockLength, options.resamples, options.rngSeed);
    const double alpha = 1.0 - options.confidence;
    result.lower = std::exp(Quantile(means, alpha / 2.0));
    result.upper = std::exp(Quantile(std::move(means), 1.0 - alpha / 2.0));
    return result;
}

DominantSet DominantValues(const std::vector<double>& values, double fraction) {
    std::vector<size_t> order;
    double total = 0.0;
    for (size_t i = 0; i < values.size(); ++i)
        if (!std::isnan(values[i])) {
            FOVRT_CHECK_OP(values[i], >=, 0.0);
            order.push_back(i);
            total += values[i];
        }
    DominantSet set;
    if (order.empty() || !(total > 0.0)) return set;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return values[a] > values[b]; });
    double sum = 0.0;
    for (size_t i : order) {
        set.indices.push_back(i);
        sum += values[i];
        if (sum >= fraction * total) break;
    }
    set.share = sum / total;
    return set;
}

}  // namespace fovrt
