// Synthetic FrameInputs for the SVGF tests: small images, fixed seeds, known clean signals.
#pragma once

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "core/frame_inputs.h"
#include "denoise/denoiser.h"
#include "denoise/gradient_strata.h"
#include "denoise/reference/svgf_ref.h"

namespace fovrt::test {

// Static scene: rows < 4 background; left half object 1 (depth slope in x), right half object 2
// (tilted normal), centre square object 3 (nearer, emissive). Clean illumination from
// `direct(x, y)` / `indirect(x, y)`, plus Gaussian noise of standard deviation sigma(x, y) / sqrt(n).
struct StaticScene {
    int width = 64, height = 64;
    std::function<float(int, int)> direct = [](int, int) { return 1.0f; };
    std::function<float(int, int)> indirect = [](int, int) { return 0.5f; };
    std::function<float(int, int)> sigma = [](int, int) { return 0.0f; };
    std::function<uint16_t(int, int)> samples = [](int, int) { return uint16_t(1); };

    uint32_t ObjectAt(int x, int y) const {
        if (y < 4) return kNoObject;
        if (std::abs(x - width / 2) < 8 && std::abs(y - height / 2) < 8) return 3;
        return x < width / 2 ? 1u : 2u;
    }

    FrameInputs Frame(uint32_t frame, uint32_t seed = 1) const {
        FrameInputs f;
        f.Allocate(width, height);
        f.frameIndex = frame;
        std::mt19937 rng(seed * 7919u + frame);
        std::normal_distribution<float> normal(0.0f, 1.0f);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                uint32_t id = ObjectAt(x, y);
                f.prevPixel(x, y) = vec2(x + 0.5f, y + 0.5f);
                uint16_t n = samples(x, y);
                f.sampleCount(x, y) = n;
                float s = sigma(x, y) / std::sqrt(float(n));
                float nd = normal(rng), ni = normal(rng);
                if (id == kNoObject) {
                    f.emission(x, y) = vec3(0.2f, 0.3f, 0.4f);
                    continue;
                }
                f.objectId(x, y) = id;
                f.linearDepth(x, y) = id == 1 ? 5.0f + 0.01f * float(x) : id == 2 ? 6.0f : 3.0f;
                f.depthGradient(x, y) = id == 1 ? vec2(0.01f, 0.0f) : vec2(0.0f);
                f.normal(x, y) = id == 2 ? glm::normalize(vec3(0.3f, 0.0f, 1.0f)) : vec3(0, 0, 1);
                f.albedo(x, y) = id == 1 ? vec3(0.8f, 0.6f, 0.4f) : id == 2 ? vec3(0.5f) : vec3(0.9f, 0.9f, 0.2f);
                f.emission(x, y) = id == 3 ? vec3(0.1f, 0.0f, 0.0f) : vec3(0.0f);
                f.direct(x, y) = vec3(std::max(0.0f, direct(x, y) + s * nd));
                f.indirect(x, y) = vec3(std::max(0.0f, indirect(x, y) + s * ni));
            }
        return f;
    }
};

// Frame `frame` of `scene` with the faults the history must survive: a 4×4 block at (10, 10) that
// changed object (a disocclusion: history 1 there), a NaN at (40, 40), an Inf at (41, 40) and a
// negative sample at (42, 40) (two non-finite samples, kept out of every history).
inline FrameInputs FaultyFrame(const StaticScene& scene, uint32_t frame) {
    FrameInputs f = scene.Frame(frame);
    for (int y = 10; y < 14; ++y)
        for (int x = 10; x < 14; ++x) f.objectId(x, y) = 7;
    f.direct(40, 40) = vec3(std::nanf(""), 1.0f, 1.0f);
    f.indirect(41, 40) = vec3(INFINITY, 0.0f, 0.0f);
    f.direct(42, 40) = vec3(-1.0f, 0.5f, 0.5f);
    return f;
}

// Random inputs: random patches of object ids and depths, sub-pixel motion, HDR noise.
inline FrameInputs RandomFrame(int w, int h, uint32_t seed, uint32_t frame) {
    FrameInputs f;
    f.Allocate(w, h);
    f.frameIndex = frame;
    std::mt19937 rng(seed);  // geometry: same every frame
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const int patch = 8;
    std::vector<uint32_t> ids;
    std::vector<float> depths;
    std::vector<vec3> normals;
    for (int i = 0; i < (w / patch + 1) * (h / patch + 1); ++i) {
        ids.push_back(u(rng) < 0.1f ? kNoObject : uint32_t(u(rng) * 4));
        depths.push_back(2.0f + 8.0f * u(rng));
        normals.push_back(glm::normalize(vec3(u(rng) - 0.5f, u(rng) - 0.5f, 1.0f)));
    }
    std::mt19937 frameRng(seed * 31u + frame * 1013u + 7u);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            int pi = (y / patch) * (w / patch + 1) + x / patch;
            uint32_t id = ids[size_t(pi)];
            f.prevPixel(x, y) = vec2(x + 0.5f + 0.3f * std::sin(0.1f * float(y) + float(frame)),
                                     y + 0.5f + 0.2f * std::cos(0.13f * float(x)));
            f.sampleCount(x, y) = uint16_t(1 + (x * 7 + y * 3) % 8);
            f.albedo(x, y) = vec3(0.2f + 0.6f * u(frameRng), 0.5f, 0.7f);
            if (id == kNoObject) continue;
            f.objectId(x, y) = id;
            f.linearDepth(x, y) = depths[size_t(pi)] + 0.02f * float(x % patch);
            f.depthGradient(x, y) = vec2(0.02f, 0.0f);
            f.normal(x, y) = normals[size_t(pi)];
            f.emission(x, y) = vec3(id == 3 ? 0.5f : 0.0f);
            auto hdr = [&] { float v = u(frameRng); return v * v * 4.0f; };
            f.direct(x, y) = vec3(hdr(), hdr(), hdr());
            f.indirect(x, y) = vec3(hdr(), hdr(), hdr());
        }
    return f;
}

// RandomFrame whose patch-edge pixels (x % 8 == 0) move onto the centre of their left neighbour,
// in the next patch: their one bilinear tap (weight 1) sees another surface and fails, and the 3×3
// fallback around it finds their own patch's column. Exercises the reprojection's box pass.
inline FrameInputs FallbackFrame(int w, int h, uint32_t seed, uint32_t frame) {
    FrameInputs f = RandomFrame(w, h, seed, frame);
    for (int y = 0; y < h; ++y)
        for (int x = 8; x < w; x += 8) f.prevPixel(x, y) = vec2(float(x) - 0.5f, float(y) + 0.5f);
    return f;
}

// RandomFrame (or FallbackFrame) with per-frame random sample counts (1–16) and A-SVGF gradient
// samples (some strata twice, some none, one outside the grid): inputs for every variant.
inline FrameInputs RandomTwoHistoryFrame(int w, int h, uint32_t frame, bool boxFallback = false) {
    FrameInputs f = boxFallback ? FallbackFrame(w, h, 5, frame) : RandomFrame(w, h, 5, frame);
    std::mt19937 rng(1000 + frame);
    std::uniform_int_distribution<int> spp(1, 16), off(0, 2);
    std::uniform_real_distribution<float> lum(0.0f, 4.0f), u(0.0f, 1.0f);
    for (size_t i = 0; i < f.sampleCount.size(); ++i) f.sampleCount[i] = uint16_t(spp(rng));
    const ivec2 grid = StratumGridSize(w, h);
    for (int sy = 0; sy < grid.y; ++sy)
        for (int sx = 0; sx < grid.x; ++sx) {
            const int copies = u(rng) < 0.3f ? 0 : (u(rng) < 0.1f ? 2 : 1);
            for (int k = 0; k < copies; ++k) {
                GradientSample s;
                s.stratum = ivec2(sx, sy);
                s.pixel =
                    glm::min(ivec2(sx * 3 + off(rng), sy * 3 + off(rng)), ivec2(w - 1, h - 1));
                s.prevPixel = s.pixel;
                s.newLuminance = lum(rng);
                s.oldLuminance = u(rng) < 0.5f ? s.newLuminance : lum(rng);
                f.gradientSamples.push_back(s);
            }
        }
    GradientSample outside;
    outside.stratum = ivec2(grid.x + 3, 0);
    outside.pixel = ivec2(0, 0);
    outside.newLuminance = 1.0f;
    outside.oldLuminance = 0.0f;
    f.gradientSamples.push_back(outside);
    return f;
}

// `f` (frame `frame`) with pixels that have no path sample, as a periphery below 1 spp gives them:
// sample count 0 and colour 0 at one pixel of every 2×2 block (which one moves with the frame), and
// from frame 1 on a disoccluded 12×8 block (previous pixel off-screen) whose left half has no sample
// at all, so that its pixels hold nothing. A-SVGF's gradient-sample pixels keep their n (the
// renderer never draws a gradient sample from a pixel without one).
inline FrameInputs WithZeroSamples(FrameInputs f, uint32_t frame) {
    const int w = f.width(), h = f.height();
    Plane<uint8_t> gradientPixel(w, h, uint8_t(0));
    for (const GradientSample& g : f.gradientSamples)
        if (f.objectId.InBounds(g.pixel.x, g.pixel.y)) gradientPixel(g.pixel.x, g.pixel.y) = 1;
    const int bx = w / 3, by = h / 3;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool block = frame > 0 && x >= bx && x < bx + 12 && y >= by && y < by + 8;
            if (block) f.prevPixel(x, y) = vec2(-1.0f);
            const bool none = (block && x < bx + 6) || ((x & 1) + 2 * (y & 1)) == int(frame % 4);
            if (!none || gradientPixel(x, y)) continue;
            f.sampleCount(x, y) = 0;
            f.direct(x, y) = vec3(0.0f);
            f.indirect(x, y) = vec3(0.0f);
        }
    return f;
}

inline FrameInputs ZeroSampleFrame(int w, int h, uint32_t seed, uint32_t frame) {
    return WithZeroSamples(RandomFrame(w, h, seed, frame), frame);
}

// Pixels of `cur` that the reference reprojects from `prev` through the 3×3 fallback.
inline int CountBoxFallbackPixels(const FrameInputs& cur, const FrameInputs& prev) {
    int count = 0;
    for (int y = 0; y < cur.height(); ++y)
        for (int x = 0; x < cur.width(); ++x) {
            const ReprojectionTaps taps = FindReprojectionTaps(cur, GeometryOf(prev), x, y);
            count += taps.box && taps.count > 0;
        }
    return count;
}

inline float TemporalError(const Plane<vec3>& a, const Plane<vec3>& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) sum += std::abs(Luminance(a[i]) - Luminance(b[i]));
    return float(sum / double(a.size()));
}

inline std::vector<float> AsFloats(const std::vector<uint8_t>& bytes) {
    std::vector<float> out(bytes.size() / 4);
    std::memcpy(out.data(), bytes.data(), out.size() * 4);
    return out;
}

}  // namespace fovrt::test
