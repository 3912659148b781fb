#include "metrics/filter.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace fovrt::metrics_detail {

void ParallelRows(int height, const std::function<void(int)>& body) {
    tbb::parallel_for(tbb::blocked_range<int>(0, height, 8), [&](const tbb::blocked_range<int>& range) {
        for (int y = range.begin(); y < range.end(); ++y) body(y);
    });
}

namespace {

// Σ of kernel taps whose source index i + k − r lies in [0, n).
template <typename T>
T InsideSum(const std::vector<T>& k, int i, int n) {
    const int r = int(k.size() / 2);
    T s = 0;
    for (int t = 0; t < int(k.size()); ++t) {
        int j = i + t - r;
        if (j >= 0 && j < n) s += k[size_t(t)];
    }
    return s;
}

}  // namespace

template <typename T>
Plane<T> ConvolveSeparable(const Plane<T>& in, const std::vector<T>& kx, const std::vector<T>& ky, Border border) {
    const int w = in.width(), h = in.height();
    const int rx = int(kx.size() / 2), ry = int(ky.size() / 2);
    T sumX = 0, sumY = 0;
    for (T v : kx) sumX += v;
    for (T v : ky) sumY += v;
    // Renormalisation factors per column / row (1 in the interior).
    std::vector<T> scaleX(size_t(w), 1.0f), scaleY(size_t(h), 1.0f);
    if (border == Border::kRenormalise) {
        for (int x = 0; x < w; ++x) scaleX[size_t(x)] = sumX / InsideSum(kx, x, w);
        for (int y = 0; y < h; ++y) scaleY[size_t(y)] = sumY / InsideSum(ky, y, h);
    }
    auto sample = [&](const T* row, int i, int n) -> T {
        if (i >= 0 && i < n) return row[i];
        return border == Border::kReplicate ? row[std::clamp(i, 0, n - 1)] : 0.0f;
    };

    Plane<T> tmp(w, h), out(w, h);
    ParallelRows(h, [&](int y) {
        const T* src = &in(0, y);
        T* dst = &tmp(0, y);
        for (int x = 0; x < w; ++x) {
            T s = 0;
            if (x >= rx && x + rx < w) {
                const T* p = src + (x - rx);
                for (size_t t = 0; t < kx.size(); ++t) s += kx[t] * p[t];
            } else {
                for (int t = 0; t < int(kx.size()); ++t) s += kx[size_t(t)] * sample(src, x + t - rx, w);
            }
            dst[x] = s * scaleX[size_t(x)];
        }
    });
    ParallelRows(h, [&](int y) {
        T* dst = &out(0, y);
        std::fill(dst, dst + w, 0.0f);
        for (int t = 0; t < int(ky.size()); ++t) {
            int yy = y + t - ry;
            if (yy < 0 || yy >= h) {
                if (border == Border::kRenormalise) continue;
                yy = std::clamp(yy, 0, h - 1);
            }
            const T k = ky[size_t(t)];
            const T* src = &tmp(0, yy);
            for (int x = 0; x < w; ++x) dst[x] += k * src[x];
        }
        const T s = scaleY[size_t(y)];
        for (int x = 0; x < w; ++x) dst[x] *= s;
    });
    return out;
}

template Plane<float> ConvolveSeparable(const Plane<float>&, const std::vector<float>&, const std::vector<float>&,
                                        Border);
template Plane<double> ConvolveSeparable(const Plane<double>&, const std::vector<double>&,
                                         const std::vector<double>&, Border);

}  // namespace fovrt::metrics_detail
