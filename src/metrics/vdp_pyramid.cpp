#include "metrics/vdp_pyramid.h"

#include <algorithm>
#include <cmath>

#include "metrics/filter.h"

namespace fovrt {

namespace {

constexpr float kA = 0.4f;
constexpr float kKernel[5] = {0.25f - kA / 2.0f, 0.25f, kA, 0.25f, 0.25f - kA / 2.0f};

// 1D reduce of n samples (stride apart) into (n+1)/2: zero-padded 5-tap filter at even positions
// plus the reference's mirror corrections at both ends; `oddRule` selects the end correction.
void Reduce1D(const float* in, int n, size_t stride, float* out, size_t outStride, bool oddRule) {
    const int m = (n + 1) / 2;
    auto at = [&](int i) {
        float s = 0.0f;
        for (int k = 0; k < 5; ++k) {
            const int j = 2 * i + k - 2;
            if (j >= 0 && j < n) s += kKernel[k] * in[size_t(j) * stride];
        }
        out[size_t(i) * outStride] = s;
    };
    // Outputs whose five taps all lie inside, i in [1, (n − 3)/2], without the bounds tests so
    // the loop vectorises (the same sums in the same order: 0 + the first product is that product).
    const int interiorEnd = std::max((n - 1) / 2, 1);  // one past the last interior output
    at(0);
    for (int i = 1; i < interiorEnd; ++i) {
        const float* x = in + size_t(2 * i - 2) * stride;
        float s = kKernel[0] * x[0];
        s += kKernel[1] * x[stride];
        s += kKernel[2] * x[2 * stride];
        s += kKernel[3] * x[3 * stride];
        s += kKernel[4] * x[4 * stride];
        out[size_t(i) * outStride] = s;
    }
    for (int i = interiorEnd; i < m; ++i) at(i);
    out[0] += in[0] * kKernel[1] + in[stride] * kKernel[0];
    float& last = out[size_t(m - 1) * outStride];
    if (oddRule) last += in[size_t(n - 1) * stride] * kKernel[3] + in[size_t(n - 2) * stride] * kKernel[4];
    else last += in[size_t(n - 1) * stride] * kKernel[4];
}

// Source index of each of the n + 4 samples of the zero-interleaved, padded signal the reference
// filters to expand `inCount` samples to n (−1 = zero).
std::vector<int> ExpandSources(int n, int inCount) {
    std::vector<int> src(size_t(n) + 4, -1);
    for (int j = 0; 2 + 2 * j < n + 2 && j < inCount; ++j) src[size_t(2 + 2 * j)] = j;
    src[0] = 0;
    src[size_t(n + 4 - 2 + (n % 2))] = inCount - 1;
    return src;
}

}  // namespace

Plane<float> VdpGaussReduce(const Plane<float>& x) {
    Plane<float> out, rows;
    VdpGaussReduce(x, out, rows);
    return out;
}

void VdpGaussReduce(const Plane<float>& x, Plane<float>& out, Plane<float>& rows) {
    const int w = x.width(), h = x.height();
    const int h2 = (h + 1) / 2, w2 = (w + 1) / 2;
    const bool oddRule = (h % 2) == 1;  // the reference tests the height for both directions
    rows.ResizeForOverwrite(w, h2);  // every pixel of both is written below
    out.ResizeForOverwrite(w2, h2);
    // Vertical pass row by row (the same sums as Reduce1D down each column).
    metrics_detail::ParallelRows(h2, [&](int i) {
        float* dst = &rows(0, i);
        std::fill(dst, dst + w, 0.0f);
        auto add = [&](int j, float g) {
            const float* src = &x(0, j);
            for (int c = 0; c < w; ++c) dst[c] += g * src[c];
        };
        for (int k = 0; k < 5; ++k) {
            const int j = 2 * i + k - 2;
            if (j >= 0 && j < h) add(j, kKernel[k]);
        }
        if (i == 0) add(0, kKernel[1]), add(1, kKernel[0]);
        if (i == h2 - 1) {
            if (oddRule) add(h - 1, kKernel[3]), add(h - 2, kKernel[4]);
            else add(h - 1, kKernel[4]);
        }
    });
    metrics_detail::ParallelRows(h2, [&](int r) { Reduce1D(&rows(0, r), w, 1, &out(0, r), 1, oddRule); });
}

Plane<float> VdpGaussExpand(const Plane<float>& x, int w, int h) {
    Plane<float> out, rows;
    VdpGaussExpand(x, w, h, out, rows);
    return out;
}

void VdpGaussExpand(const Plane<float>& x, int w, int h, Plane<float>& out, Plane<float>& rows) {
    const std::vector<int> srcRow = ExpandSources(h, x.height());
    const std::vector<int> srcCol = ExpandSources(w, x.width());
    rows.ResizeForOverwrite(x.width(), h);  // every pixel of both is written below
    out.ResizeForOverwrite(w, h);
    metrics_detail::ParallelRows(h, [&](int r) {
        float* dst = &rows(0, r);
        std::fill(dst, dst + x.width(), 0.0f);
        for (int k = 0; k < 5; ++k) {
            const int s = srcRow[size_t(r + k)];
            if (s < 0) continue;
            const float g = 2.0f * kKernel[k];
            const float* src = &x(0, s);
            for (int c = 0; c < x.width(); ++c) dst[c] += g * src[c];
        }
    });
    metrics_detail::ParallelRows(h, [&](int r) {
        const float* src = &rows(0, r);
        float* dst = &out(0, r);
        auto at = [&](int c) {
            float s = 0.0f;
            for (int k = 0; k < 5; ++k) {
                const int j = srcCol[size_t(c + k)];
                if (j >= 0) s += 2.0f * kKernel[k] * src[j];
            }
            dst[c] = s;
        };
        // Inside, c in [2, w − 3], the taps read no edge replica: output 2m sums taps 0, 2, 4 at
        // inputs m − 1, m, m + 1, and 2m + 1 taps 1, 3 at m, m + 1 (the zero-interleaved signal).
        // The same sums in the same order as `at`, without its lookups, so the loop vectorises.
        const float g0 = 2.0f * kKernel[0], g1 = 2.0f * kKernel[1], g2 = 2.0f * kKernel[2], g3 = 2.0f * kKernel[3],
                    g4 = 2.0f * kKernel[4];
        const int pairs = std::max((w - 4) / 2, 0);  // m = 1 .. pairs: outputs 2 .. 2·pairs + 1
        for (int c = 0; c < std::min(2, w); ++c) at(c);
        for (int m = 1; m <= pairs; ++m) {
            float even = g0 * src[m - 1];
            even += g2 * src[m];
            even += g4 * src[m + 1];
            float odd = g1 * src[m];
            odd += g3 * src[m + 1];
            dst[2 * m] = even;
            dst[2 * m + 1] = odd;
        }
        for (int c = std::max(2 * pairs + 2, 2); c < w; ++c) at(c);
    });
}

int VdpBandCount(int width, int height, double ppd) {
    const int maxLevels = int(std::floor(std::log2(double(std::min(width, height))))) - 1;
    // Candidate peak frequencies: ppd/2, then 0.3228·2^−k·ppd/2 for k = 0..13.
    int firstInvalid = -1;
    for (int i = 0; i < 15 && firstInvalid < 0; ++i) {
        const double f = (i == 0 ? 1.0 : std::pow(2.0, -(i - 1)) * 0.3228) * ppd / 2.0;
        if (f <= 0.5) firstInvalid = i;
    }
    const int count = firstInvalid < 0 ? maxLevels : firstInvalid + 1;
    return std::clamp(count, 0, maxLevels);
}

std::vector<double> VdpBandFrequencies(int width, int height, double ppd) {
    const int bands = VdpBandCount(width, height, ppd);
    std::vector<double> f(size_t(bands) + 1);
    for (int i = 0; i <= bands; ++i) f[size_t(i)] = (i == 0 ? 1.0 : 0.3228 * std::pow(2.0, -(i - 1))) * ppd / 2.0;
    return f;
}

VdpContrastPyramid VdpDecompose(const std::vector<const Plane<float>*>& images, int adaptingImage, int bands) {
    VdpContrastPyramid pyr;
    VdpDecompose(images, adaptingImage, bands, pyr);
    return pyr;
}

void VdpDecompose(const std::vector<const Plane<float>*>& images, int adaptingImage, int bands,
                  VdpContrastPyramid& pyr) {
    const size_t n = images.size();
    pyr.contrast.resize(size_t(bands));
    pyr.adaptation.resize(size_t(bands));
    pyr.scratch.resize(size_t(bands));
    std::vector<const Plane<float>*> level = images;  // band 0 reads the inputs themselves
    for (int b = 0; b < bands; ++b) {
        const int w = level[0]->width(), h = level[0]->height();
        VdpContrastPyramid::BandScratch& s = pyr.scratch[size_t(b)];
        s.next.resize(n);
        for (size_t i = 0; i < n; ++i) VdpGaussReduce(*level[i], s.next[i], s.reduceRows);
        VdpGaussExpand(s.next[size_t(adaptingImage)], w, h, s.expandedAdapting, s.expandRows);
        Plane<float>& adapt = pyr.adaptation[size_t(b)];
        adapt.ResizeForOverwrite(w, h);
        for (size_t p = 0; p < adapt.size(); ++p) adapt[p] = std::max(s.expandedAdapting[p], 0.1f);
        const float gain = b == 0 ? 1.0f : 2.0f;
        pyr.contrast[size_t(b)].resize(n);
        for (size_t i = 0; i < n; ++i) {
            const Plane<float>* e = &s.expandedAdapting;
            if (i != size_t(adaptingImage)) VdpGaussExpand(s.next[i], w, h, s.expanded, s.expandRows), e = &s.expanded;
            const Plane<float>& l = *level[i];
            Plane<float>& c = pyr.contrast[size_t(b)][i];
            c.ResizeForOverwrite(w, h);
            for (size_t p = 0; p < c.size(); ++p) c[p] = std::min((l[p] - (*e)[p]) / adapt[p], 1000.0f) * gain;
        }
        for (size_t i = 0; i < n; ++i) level[i] = &s.next[i];
    }
}

Plane<float> VdpReconstruct(const std::vector<Plane<float>>& bands) {
    // Base band of the zero image: zero, one level below the last band.
    const Plane<float>& last = bands.back();
    Plane<float> img((last.width() + 1) / 2, (last.height() + 1) / 2, 0.0f);
    for (int b = int(bands.size()) - 1; b >= 0; --b) {
        const Plane<float>& band = bands[size_t(b)];
        img = VdpGaussExpand(img, band.width(), band.height());
        for (size_t p = 0; p < img.size(); ++p) img[p] += band[p];
    }
    return img;
}

}  // namespace fovrt
