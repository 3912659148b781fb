#include "denoise/reference/rae_features.h"

#include <algorithm>
#include <cmath>

namespace fovrt {
namespace {

float Clean(float v) { return std::isfinite(v) && v > 0.0f ? v : 0.0f; }

}  // namespace

void RaeFeatures(const FrameInputs& in, Tensor& f) {
    const int w = in.width(), h = in.height();
    f = Tensor(kRaeFeatureChannels, h, w);
    const mat3 view = mat3(in.camera.View());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const vec3 c = in.direct(x, y) + in.indirect(x, y);
            f.At(0, y, x) = Clean(c.x);
            f.At(1, y, x) = Clean(c.y);
            f.At(2, y, x) = Clean(c.z);
            const vec3 n = view * in.normal(x, y);
            f.At(3, y, x) = n.x;
            f.At(4, y, x) = n.y;
            const float d = in.linearDepth(x, y);
            f.At(5, y, x) = std::isfinite(d) && d >= 0.0f ? d / (d + 1.0f) : 1.0f;
            f.At(6, y, x) = in.roughness(x, y);
            f.At(7, y, x) = std::log2(float(std::max<uint16_t>(in.sampleCount(x, y), 1))) * 0.25f;
        }
    // Surface pixels a sub-1-spp mask left without a path sample hold 0 illumination; the
    // background holds none to fill from or into.
    std::vector<uint8_t> known(size_t(w) * h), fill(size_t(w) * h);
    bool anyEmpty = false;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool surface = in.objectId(x, y) != kNoObject, sampled = in.sampleCount(x, y) > 0;
            known[size_t(y) * w + x] = surface && sampled;
            fill[size_t(y) * w + x] = surface && !sampled;
            anyEmpty |= surface && !sampled;
        }
    if (anyEmpty) RaeFillEmptyPixels(known, fill, f);
}

void RaeFillEmptyPixels(const std::vector<uint8_t>& known, const std::vector<uint8_t>& fill, Tensor& f) {
    // Level k: the colour sums and known-pixel counts of each 2^k block (pull).
    struct Level {
        int w, h;
        std::vector<double> sum;  // 3 per cell
        std::vector<double> count;
    };
    std::vector<Level> levels;
    Level base{f.w, f.h, std::vector<double>(size_t(3) * f.w * f.h, 0.0), std::vector<double>(size_t(f.w) * f.h, 0.0)};
    for (int y = 0; y < f.h; ++y)
        for (int x = 0; x < f.w; ++x) {
            const size_t i = size_t(y) * f.w + x;
            if (!known[i]) continue;
            base.count[i] = 1.0;
            for (int c = 0; c < 3; ++c) base.sum[3 * i + c] = f.At(c, y, x);
        }
    levels.push_back(std::move(base));
    while (levels.back().w > 1 || levels.back().h > 1) {
        const Level& fine = levels.back();
        Level coarse{(fine.w + 1) / 2, (fine.h + 1) / 2, {}, {}};
        coarse.sum.assign(size_t(3) * coarse.w * coarse.h, 0.0);
        coarse.count.assign(size_t(coarse.w) * coarse.h, 0.0);
        for (int y = 0; y < fine.h; ++y)
            for (int x = 0; x < fine.w; ++x) {
                const size_t i = size_t(y) * fine.w + x, j = size_t(y / 2) * coarse.w + x / 2;
                coarse.count[j] += fine.count[i];
                for (int c = 0; c < 3; ++c) coarse.sum[3 * j + c] += fine.sum[3 * i + c];
            }
        levels.push_back(std::move(coarse));
    }
    // Push: the mean of a cell's known pixels, or its parent's where it has none.
    std::vector<double> parent(3, 0.0);  // the 1×1 top's parent: 0, for a frame with nothing known
    int parentW = 1;
    for (size_t k = levels.size(); k-- > 0;) {
        Level& level = levels[k];
        std::vector<double> mean(size_t(3) * level.w * level.h);
        for (int y = 0; y < level.h; ++y)
            for (int x = 0; x < level.w; ++x) {
                const size_t i = size_t(y) * level.w + x;
                const size_t p = k + 1 < levels.size() ? size_t(y / 2) * parentW + x / 2 : 0;
                for (int c = 0; c < 3; ++c)
                    mean[3 * i + c] = level.count[i] > 0.0 ? level.sum[3 * i + c] / level.count[i] : parent[3 * p + c];
            }
        parent = std::move(mean);
        parentW = level.w;
    }
    for (int y = 0; y < f.h; ++y)
        for (int x = 0; x < f.w; ++x) {
            const size_t i = size_t(y) * f.w + x;
            if (fill[i] && !known[i])
                for (int c = 0; c < 3; ++c) f.At(c, y, x) = float(parent[3 * i + c]);
        }
}

vec3 RaeBalanceGains(const Tensor& f) {
    double sum[3] = {0.0, 0.0, 0.0};
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < f.h; ++y)
            for (int x = 0; x < f.w; ++x) sum[c] += f.At(c, y, x);
    const double mean = (sum[0] + sum[1] + sum[2]) / 3.0;
    vec3 gains(1.0f);
    for (int c = 0; c < 3; ++c)
        if (mean > 0.0 && sum[c] >= 1e-4 * mean) gains[c] = float(mean / sum[c]);
    return gains;
}

void RaeNetworkInput(const Tensor& f, const RaeWeights& weights, Tensor& input, vec3 gains) {
    const int L = weights.Levels();
    const int pw = RaePaddedSize(f.w, L), ph = RaePaddedSize(f.h, L);
    if (input.c != weights.inChannels || input.w != pw || input.h != ph)
        input = Tensor(weights.inChannels, ph, pw);
    else
        std::fill(input.data.begin(), input.data.end(), 0.0f);
    for (int c = 0; c < weights.inChannels; ++c)
        for (int y = 0; y < f.h; ++y)
            for (int x = 0; x < f.w; ++x) {
                const float v = f.At(c, y, x);
                input.At(c, y, x) = c < 3 ? std::pow(v * gains[c], weights.gamma) : v;
            }
}

void RaeTarget(const FrameInputs& in, const Plane<vec3>& reference, Tensor& t) {
    const int w = in.width(), h = in.height();
    t = Tensor(3, h, w);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (in.objectId(x, y) == kNoObject) continue;
            const vec3 a = glm::max(in.albedo(x, y), vec3(1e-3f));
            const vec3 d = (reference(x, y) - in.emission(x, y)) / a;
            for (int c = 0; c < 3; ++c) t.At(c, y, x) = Clean(d[c]);
        }
}

void RaeRemodulate(const FrameInputs& in, const Tensor& y, float gamma, Plane<vec3>& output, vec3 gains) {
    const int w = in.width(), h = in.height();
    output.Resize(w, h);
    const float inv = 1.0f / gamma;
    for (int py = 0; py < h; ++py)
        for (int px = 0; px < w; ++px) {
            vec3 illum;
            for (int c = 0; c < 3; ++c) illum[c] = std::pow(std::max(y.At(c, py, px), 0.0f), inv) / gains[c];
            output(px, py) = in.albedo(px, py) * illum + in.emission(px, py);
        }
}

}  // namespace fovrt
