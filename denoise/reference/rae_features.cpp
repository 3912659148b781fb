#include "denoise/reference/rae_features.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace fovrt {
namespace {

float Clean(float v) { return std::isfinite(v) && v > 0.0f ? v : 0.0f; }

}  // namespace

void RaeFeatures(const FrameInputs& in, Tensor& f) {
    const int w = in.width(), h = in.height();
    f = Tensor(kRaeFeatureChannels, h, w);
    const mat3 view = mat3(in.camera.View());
    bool anyEmpty = false;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            anyEmpty |= in.sampleCount(x, y) == 0 && in.objectId(x, y) != kNoObject;
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
    // background holds none to fill from or into. At 1 spp and above nothing is allocated.
    if (!anyEmpty) return;
    std::vector<uint8_t> known(size_t(w) * h), fill(size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool surface = in.objectId(x, y) != kNoObject, sampled = in.sampleCount(x, y) > 0;
            known[size_t(y) * w + x] = surface && sampled;
            fill[size_t(y) * w + x] = surface && !sampled;
        }
    RaeFillEmptyPixels(known, fill, f);
}

void RaeFillEmptyPixels(const std::vector<uint8_t>& known, const std::vector<uint8_t>& fill, Tensor& f) {
    FOVRT_CHECK(f.c >= kRaeFeatureChannels && known.size() == size_t(f.w) * f.h && fill.size() == known.size());
    // Levels 1, 2, …: per 2^k block the sums of the colour and of the sample-count feature over its
    // known pixels and their count (pull), then, top down and in place, their means or the
    // parent's where the block holds none (push). Level 0 is the features themselves; the pyramid
    // adds a third of the pixels at 20 bytes each.
    struct Cell {
        vec3 colour{0.0f};
        float samples = 0.0f;  // the sample-count feature (channel 7)
        float count = 0.0f;
    };
    struct Level {
        int w, h;
        std::vector<Cell> cells;
        Cell& At(int x, int y) { return cells[size_t(y) * w + x]; }
    };
    std::vector<Level> levels;
    levels.push_back({(f.w + 1) / 2, (f.h + 1) / 2, {}});
    levels[0].cells.resize(size_t(levels[0].w) * levels[0].h);
    for (int y = 0; y < f.h; ++y)
        for (int x = 0; x < f.w; ++x)
            if (known[size_t(y) * f.w + x]) {
                Cell& c = levels[0].At(x / 2, y / 2);
                c.colour += vec3(f.At(0, y, x), f.At(1, y, x), f.At(2, y, x));
                c.samples += f.At(7, y, x);
                c.count += 1.0f;
            }
    while (levels.back().w > 1 || levels.back().h > 1) {
        Level coarse{(levels.back().w + 1) / 2, (levels.back().h + 1) / 2, {}};
        coarse.cells.resize(size_t(coarse.w) * coarse.h);
        Level& fine = levels.back();
        for (int y = 0; y < fine.h; ++y)
            for (int x = 0; x < fine.w; ++x) {
                Cell& c = coarse.At(x / 2, y / 2);
                c.colour += fine.At(x, y).colour;
                c.samples += fine.At(x, y).samples;
                c.count += fine.At(x, y).count;
            }
        levels.push_back(std::move(coarse));
    }
    for (size_t k = levels.size(); k-- > 0;)
        for (int y = 0; y < levels[k].h; ++y)
            for (int x = 0; x < levels[k].w; ++x) {
                Cell& c = levels[k].At(x, y);
                // The top's parent is black: a frame with nothing known fills with 0.
                const Cell parent = k + 1 < levels.size() ? levels[k + 1].At(x / 2, y / 2) : Cell{};
                c.colour = c.count > 0.0f ? c.colour / c.count : parent.colour;
                c.samples = c.count > 0.0f ? c.samples / c.count : parent.samples;
            }
    for (int y = 0; y < f.h; ++y)
        for (int x = 0; x < f.w; ++x) {
            const size_t i = size_t(y) * f.w + x;
            if (!fill[i] || known[i]) continue;
            const Cell& mean = levels[0].At(x / 2, y / 2);
            for (int c = 0; c < 3; ++c) f.At(c, y, x) = mean.colour[c];
            f.At(7, y, x) = mean.samples;
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
