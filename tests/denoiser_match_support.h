// The reference-vs-Vulkan check the denoiser tests on real frames share: a denoiser's C++
// reference and its Vulkan passes fed the same frames must agree to 2e-3 relative
// (|gpu − cpu| / (1 + |cpu|)) on every pixel and channel, with no non-finite output.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/frame_inputs.h"
#include "denoise/denoiser_factory.h"
#include "denoise/params.h"
#include "pipeline/frame_pipeline.h"
#include "vk_test_support.h"

namespace fovrt::test {

// The first four frames `config` renders: the inputs the real-frame checks feed (frame 1 on carries
// A-SVGF's gradient samples).
inline std::vector<StereoFrame> RenderFourFrames(const RunConfig& config) {
    FramePipeline pipeline(config);
    std::vector<StereoFrame> frames(4);
    for (size_t f = 0; f < frames.size(); ++f) pipeline.Render(uint32_t(f), frames[f]);
    REQUIRE(frames[1].eyes[0].inputs.gradientSamples.size() > 0);
    return frames;
}

// The left eye's inputs of `frames`, in order.
inline std::vector<const FrameInputs*> LeftEyeInputs(const std::vector<StereoFrame>& frames) {
    std::vector<const FrameInputs*> inputs;
    for (const StereoFrame& frame : frames) inputs.push_back(&frame.eyes[0].inputs);
    return inputs;
}

inline void CheckVulkanMatchesReference(const std::string& name, const std::vector<const FrameInputs*>& frames) {
    const DenoiserParams params = ParamsForDenoiser(name, DenoiserParams{});
    auto cpu = CreateDenoiser(name, "cpu", params);
    auto gpu = CreateDenoiser(name, "auto", params, TestContext().get());
    REQUIRE(gpu->Backend() == "vulkan");
    Plane<vec3> cpuOut, gpuOut;
    for (size_t f = 0; f < frames.size(); ++f) {
        cpu->Denoise(*frames[f], cpuOut);
        gpu->Denoise(*frames[f], gpuOut);
        double maxRel = 0.0;
        size_t nonFinite = 0;
        for (size_t i = 0; i < cpuOut.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                if (!std::isfinite(gpuOut[i][c])) ++nonFinite;
                const double ref = cpuOut[i][c], got = gpuOut[i][c];
                maxRel = std::max(maxRel, std::fabs(got - ref) / (1.0 + std::fabs(ref)));
            }
        INFO(name << " frame " << f << ": max rel error " << maxRel);
        CHECK(nonFinite == 0);
        CHECK(maxRel < 2e-3);
    }
}

}  // namespace fovrt::test
