// The thesis protocol scaled to 64×64 (denoise_two_history_scene.h): a moving 8-spp fovea over a
// static noisy view at 1 spp; for each denoiser variant (C++ reference) the foveal temporal error
// (mean |Δlum| over the disc, the experiments' measure) and the foveal relMSE, summed over frames
// kFoveaWarmup..kFoveaFrames − 1. Every variant sees the same frames.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <vector>

#include "denoise/denoiser_factory.h"
#include "denoise_two_history_scene.h"
#include "metrics/image_metrics.h"

namespace fovrt::test {

struct FoveaScores {
    std::vector<double> temporal, relMse;  // per variant, in the order given
};

inline FoveaScores MovingFoveaScores(const std::vector<const char*>& names, const DenoiserParams& params) {
    const size_t count = names.size();
    std::vector<std::unique_ptr<Denoiser>> denoisers;
    for (const char* name : names) denoisers.push_back(CreateDenoiser(name, "cpu", params));
    Plane<vec3> truth(kFoveaW, kFoveaH);
    for (int y = 0; y < kFoveaH; ++y)
        for (int x = 0; x < kFoveaW; ++x) truth(x, y) = vec3(1.5f * Truth(x, y));
    std::mt19937 rng(2024);
    FrameInputs f;
    std::vector<Plane<vec3>> out(count), prev(count);
    Plane<uint8_t> fovea(kFoveaW, kFoveaH);
    FoveaScores r{std::vector<double>(count, 0.0), std::vector<double>(count, 0.0)};
    for (int frame = 0; frame < kFoveaFrames; ++frame) {
        auto inFovea = [&](int x, int y) { return InMovingFovea(frame, x, y); };
        for (int y = 0; y < kFoveaH; ++y)
            for (int x = 0; x < kFoveaW; ++x) fovea(x, y) = inFovea(x, y) ? 1 : 0;
        NoisyFrame(f, kFoveaW, kFoveaH, uint32_t(frame), 1.0f, [&](int x, int y) { return inFovea(x, y) ? 8 : 1; },
                   rng);
        for (size_t v = 0; v < count; ++v) {
            denoisers[v]->Denoise(f, out[v]);
            if (frame >= kFoveaWarmup) {
                r.temporal[v] += TemporalError(out[v], prev[v], &fovea);
                r.relMse[v] += RelMse(out[v], truth, inFovea);
            }
            prev[v] = out[v];
        }
    }
    std::printf("moving fovea 64x64 (thesis protocol), frames %d..%d:", kFoveaWarmup, kFoveaFrames - 1);
    for (size_t v = 0; v < count; ++v) std::printf(" %s temporal %.5f relMSE %.6f;", names[v], r.temporal[v], r.relMse[v]);
    std::printf("\n");
    return r;
}

// The largest |a − b| / (1 + |a|) between two variants' outputs over 8 noisy 32×32 frames
// (NoisyFrame, σ = 1, one random sequence); `spp(x, frame)` gives column x's sample count.
inline double WorstOutputDifference(const char* nameA, const char* nameB, const DenoiserParams& params,
                                    const std::function<int(int, int)>& spp) {
    std::unique_ptr<Denoiser> da = CreateDenoiser(nameA, "cpu", params);
    std::unique_ptr<Denoiser> db = CreateDenoiser(nameB, "cpu", params);
    std::mt19937 rng(7);
    FrameInputs f;
    Plane<vec3> a, b;
    double worst = 0.0;
    for (int frame = 0; frame < 8; ++frame) {
        NoisyFrame(f, 32, 32, uint32_t(frame), 1.0f, [&](int x, int) { return spp(x, frame); }, rng);
        da->Denoise(f, a);
        db->Denoise(f, b);
        for (size_t i = 0; i < a.size(); ++i)
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, double(std::abs(a[i][c] - b[i][c]) / (1.0f + std::abs(a[i][c]))));
    }
    return worst;
}

}  // namespace fovrt::test
