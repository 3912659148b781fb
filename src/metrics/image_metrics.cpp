#include "metrics/image_metrics.h"

#include <cmath>
#include <limits>
#include <vector>

#include "metrics/filter.h"
#include "metrics/tonemap.h"

namespace fovrt {

namespace {

void CheckSameSize(const auto& a, const auto& b) {
    FOVRT_CHECK_OP(a.width(), ==, b.width());
    FOVRT_CHECK_OP(a.height(), ==, b.height());
}

// Normalised 1D Gaussian taps for offsets -radius..radius.
std::vector<double> GaussianTaps(int radius, double sigma) {
    std::vector<double> taps(size_t(2 * radius + 1));
    double sum = 0;
    for (int i = -radius; i <= radius; ++i) sum += taps[size_t(i + radius)] = std::exp(-double(i * i) / (2 * sigma * sigma));
    for (double& t : taps) t /= sum;
    return taps;
}

// Gaussian-weighted mean with the window cut at the border and renormalised (a constant image stays
// constant up to the edge). Double precision: SSIM subtracts μ² from E[x²].
Plane<double> GaussianMeanTruncated(const Plane<double>& in, const std::vector<double>& taps) {
    return metrics_detail::ConvolveSeparable(in, taps, taps, metrics_detail::Border::kRenormalise);
}

}  // namespace

Plane<float> RelMseMap(const Plane<vec3>& test, const Plane<vec3>& reference, float epsilon) {
    CheckSameSize(test, reference);
    Plane<float> map(test.width(), test.height());
    for (size_t i = 0; i < test.size(); ++i) {
        double sum = 0;
        for (int c = 0; c < 3; ++c) {
            double y = test[i][c], r = reference[i][c];
            sum += (y - r) * (y - r) / (r * r + double(epsilon));
        }
        map[i] = float(sum / 3.0);
    }
    return map;
}

double RelMse(const Plane<vec3>& test, const Plane<vec3>& reference, const Plane<uint8_t>* mask,
              float epsilon) {
    return MaskedMean(RelMseMap(test, reference, epsilon), mask);
}

Plane<float> DisplayLuma(const Plane<vec3>& hdr) {
    Plane<float> luma(hdr.width(), hdr.height());
    for (size_t i = 0; i < hdr.size(); ++i) luma[i] = Luminance(ToneMap(hdr[i]));
    return luma;
}

Plane<float> SsimMapOfLuma(const Plane<float>& x, const Plane<float>& y, float dynamicRange) {
    CheckSameSize(x, y);
    const int w = x.width(), h = x.height();
    Plane<double> dx(w, h), dy(w, h), xx(w, h), yy(w, h), xy(w, h);
    for (size_t i = 0; i < x.size(); ++i) {
        dx[i] = x[i];
        dy[i] = y[i];
        xx[i] = dx[i] * dx[i];
        yy[i] = dy[i] * dy[i];
        xy[i] = dx[i] * dy[i];
    }
    const auto taps = GaussianTaps(kSsimRadius, kSsimSigma);
    Plane<double> muX = GaussianMeanTruncated(dx, taps), muY = GaussianMeanTruncated(dy, taps);
    Plane<double> eXX = GaussianMeanTruncated(xx, taps), eYY = GaussianMeanTruncated(yy, taps),
                  eXY = GaussianMeanTruncated(xy, taps);
    const double c1 = std::pow(double(kSsimK1) * dynamicRange, 2.0);
    const double c2 = std::pow(double(kSsimK2) * dynamicRange, 2.0);
    Plane<float> map(w, h);
    for (size_t i = 0; i < map.size(); ++i) {
        double mx = muX[i], my = muY[i];
        double vx = eXX[i] - mx * mx, vy = eYY[i] - my * my, cxy = eXY[i] - mx * my;
        map[i] = float(((2 * mx * my + c1) * (2 * cxy + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2)));
    }
    return map;
}

Plane<float> SsimMap(const Plane<vec3>& test, const Plane<vec3>& reference) {
    return SsimMapOfLuma(DisplayLuma(test), DisplayLuma(reference), 1.0f);
}

double Ssim(const Plane<vec3>& test, const Plane<vec3>& reference, const Plane<uint8_t>* mask) {
    return MaskedMean(SsimMap(test, reference), mask);
}

Plane<float> TemporalErrorMap(const Plane<vec3>& current, const Plane<vec3>& previous) {
    CheckSameSize(current, previous);
    Plane<float> map(current.width(), current.height());
    for (size_t i = 0; i < map.size(); ++i) map[i] = std::abs(Luminance(current[i]) - Luminance(previous[i]));
    return map;
}

double TemporalError(const Plane<vec3>& current, const Plane<vec3>& previous, const Plane<uint8_t>* mask) {
    return MaskedMean(TemporalErrorMap(current, previous), mask);
}

double MaskedMean(const Plane<float>& map, const Plane<uint8_t>* mask) {
    if (mask) CheckSameSize(map, *mask);
    double sum = 0;
    size_t count = 0;
    for (size_t i = 0; i < map.size(); ++i) {
        if (mask && (*mask)[i] == 0) continue;
        sum += map[i];
        ++count;
    }
    return count ? sum / double(count) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace fovrt
