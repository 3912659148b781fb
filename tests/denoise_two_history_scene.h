// Synthetic inputs shared by the two-history / A-SVGF / lag tests: a static fronto-parallel plane
// (one object, constant depth and normal, static camera) whose illumination is a chosen truth plus
// Monte-Carlo-like noise of variance σ²/n
// (the project's SVGF is the reference the new denoisers must equal or beat).
#pragma once

#include <cmath>
#include <functional>
#include <random>

#include "core/frame_inputs.h"
#include "denoise/params.h"
#include "denoise/reference/svgf_family_ref.h"

namespace fovrt::test {

// Static plane: every pixel reprojects onto itself.
inline void MakeStaticPlane(FrameInputs& f, int w, int h, uint32_t frameIndex) {
    f.Allocate(w, h);
    f.frameIndex = frameIndex;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            f.albedo(x, y) = vec3(1.0f);
            f.normal(x, y) = vec3(0.0f, 0.0f, 1.0f);
            f.linearDepth(x, y) = 2.0f;
            f.depthGradient(x, y) = vec2(0.0f);
            f.objectId(x, y) = 0;
            f.prevPixel(x, y) = vec2(float(x) + 0.5f, float(y) + 0.5f);
        }
}

// The thesis's Lissajous gaze scaled to 64×64 (amplitude 20 px, 30 frames per second) and its
// fovea, a disc of radius 12 px.
inline bool InMovingFovea(int frame, int x, int y) {
    const float t = float(frame) / 30.0f;
    const vec2 gaze(32.0f + 20.0f * std::sin(2.0f * kPi * 0.4f * t + kPi / 2),
                    32.0f + 20.0f * std::sin(2.0f * kPi * 0.5f * t));
    return glm::length(vec2(float(x) + 0.5f, float(y) + 0.5f) - gaze) < 12.0f;
}

// The project's plain SVGF (C++ reference backend, denoise/reference/svgf_family_ref.h).
inline SvgfFamilyReferenceDenoiser MakeSvgf(const SvgfParams& svgf) {
    DenoiserParams params;
    params.svgf = svgf;
    return SvgfFamilyReferenceDenoiser(FindDenoiserVariant("svgf"), params);
}

// 3 + a·sin(x/6)·cos(y/9): a = 0 is a flat plane (no curvature, so spatial filtering is unbiased).
inline float Truth(int x, int y, float amplitude = 1.0f) {
    return 3.0f + amplitude * std::sin(float(x) / 6.0f) * std::cos(float(y) / 9.0f);
}

// Noisy frame: direct = truth + N(0, σ²/n), indirect = truth/2 + N(0, σ²/(4n)).
inline void NoisyFrame(FrameInputs& f, int w, int h, uint32_t frame, float sigma,
                       const std::function<int(int, int)>& spp, std::mt19937& rng, float amplitude = 1.0f) {
    MakeStaticPlane(f, w, h, frame);
    std::normal_distribution<float> g(0.0f, 1.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int n = spp(x, y);
            f.sampleCount(x, y) = uint16_t(n);
            const float s = sigma / std::sqrt(float(n));
            const float t = Truth(x, y, amplitude);
            f.direct(x, y) = vec3(t + s * g(rng), t + s * g(rng), t + s * g(rng));
            f.indirect(x, y) = vec3(0.5f * t + 0.5f * s * g(rng));
        }
}

inline constexpr int kFoveaW = 64, kFoveaH = 64, kFoveaFrames = 120, kFoveaWarmup = 30;

// relMSE (SPEC §8, ε = 0.01) over the pixels where mask(x, y) is true.
inline double RelMse(const Plane<vec3>& y, const Plane<vec3>& r,
                     const std::function<bool(int, int)>& mask) {
    double sum = 0.0;
    size_t count = 0;
    for (int py = 0; py < y.height(); ++py)
        for (int px = 0; px < y.width(); ++px) {
            if (!mask(px, py)) continue;
            for (int c = 0; c < 3; ++c) {
                const double d = double(y(px, py)[c]) - r(px, py)[c];
                sum += d * d / (double(r(px, py)[c]) * r(px, py)[c] + 0.01);
                ++count;
            }
        }
    return count ? sum / double(count) : 0.0;
}

}  // namespace fovrt::test
