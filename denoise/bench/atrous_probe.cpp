#include "denoise/bench/atrous_probe.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <random>

#include "denoise/bench/pass_bytes.h"
#include "denoise/svgf_family_plan.h"
#include "denoise/vulkan/stage_pipelines.h"
#include "denoise/vulkan/svgf_layout.h"
#include "vk/context.h"

namespace fovrt {

AtrousProbeImage MakeAtrousProbeImage(int width, int height, uint32_t seed) {
    AtrousProbeImage im;
    im.width = width;
    im.height = height;
    const size_t n = size_t(width) * size_t(height);
    im.guide.resize(n);
    im.illum0.resize(n);
    im.illum1.resize(n);
    im.depthGradient.resize(n);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * size_t(width) + size_t(x);
            const bool background = y < height / 16;
            const bool nearObject = (x / 64 + y / 48) % 3 == 0;  // depth and normal edges
            const float depth = nearObject ? 2.0f : 5.0f + 0.01f * float(x);
            const vec3 normal = glm::normalize(nearObject ? vec3(0.3f, 0.1f, 1.0f) : vec3(0.0f, 0.0f, 1.0f));
            im.guide[i] = vec4(normal, background ? -1.0f : depth);
            im.depthGradient[i] = nearObject ? vec2(0.0f) : vec2(0.01f, 0.0f);
            auto noisy = [&] {
                const float a = u(rng), b = u(rng);
                return vec4(a * a * 3.0f, b, 0.5f * a, 0.05f + 0.2f * b);  // rgb, variance
            };
            im.illum0[i] = noisy();
            im.illum1[i] = noisy();
        }
    return im;
}

AtrousProbe::AtrousProbe(VulkanContext& context, const AtrousProbeImage& image, int step)
    : context_(context), width_(image.width), height_(image.height), step_(step) {
    const size_t n = size_t(width_) * size_t(height_);
    VulkanAllocator& alloc = context.allocator();
    guide_ = alloc.CreateBuffer("probe.guide", 16 * n);
    depthGradient_ = alloc.CreateBuffer("probe.depthGradient", 8 * n);
    in_ = {alloc.CreateBuffer("probe.illum0", 16 * n), alloc.CreateBuffer("probe.illum1", 16 * n)};
    out_ = {alloc.CreateBuffer("probe.out0", 16 * n), alloc.CreateBuffer("probe.out1", 16 * n)};
    history_ = alloc.CreateBuffer("probe.history", 12 * n);  // bound, not written (no feedback)
    staging_ = alloc.CreateBuffer("probe.staging", 64 * n + 4096, MemoryUsage::Staging);
    // The pair layout the denoisers' iterations ≥ 1 use (no feedback: the history is bound, unwritten).
    std::array<const Buffer*, SVGF_ATROUS_PAIR_BINDINGS> slots{};
    slots[SVGF_ATROUS_B_GUIDE] = &guide_;
    slots[SVGF_ATROUS_B_DEPTH_GRAD] = &depthGradient_;
    slots[SVGF_ATROUS_B_ILLUM_IN] = &in_[0];
    slots[SVGF_ATROUS_B_ILLUM_OUT] = &out_[0];
    slots[SVGF_ATROUS_B_HIST_COLOR] = &history_;
    slots[SVGF_ATROUS_B_ILLUM_IN2] = &in_[1];
    slots[SVGF_ATROUS_B_ILLUM_OUT2] = &out_[1];
    slots[SVGF_ATROUS_B_HIST_COLOR2] = &history_;
    for (int unit = 0; unit < 2; ++unit) {
        const PipelineKey key = AtrousPipeline(DenoiserParams{}, true, false, false, unit == 1);
        pipelines_[size_t(unit)] = MakeStagePipeline(context, key, sizeof(SvgfAtrousPush), 1);
        sets_[size_t(unit)] = pipelines_[size_t(unit)].MakeSet(slots);
    }
    timestamps_ = TimestampPool(context, 1);
    CommandRecorder rec(context);
    size_t off = rec.Upload(image.guide.data(), 16 * n, staging_, 0, guide_);
    off = rec.Upload(image.depthGradient.data(), 8 * n, staging_, off, depthGradient_);
    off = rec.Upload(image.illum0.data(), 16 * n, staging_, off, in_[0]);
    rec.Upload(image.illum1.data(), 16 * n, staging_, off, in_[1]);
    rec.Barrier();
    rec.Submit();
}

AtrousProbeRun AtrousProbe::Run(bool unitWeights, int runs) {
    const size_t n = size_t(width_) * size_t(height_);
    const SvgfParams p;
    const ivec2 size(width_, height_);
    const SvgfAtrousPush push{size, step_, p.sigmaDepth, p.sigmaNormal, p.sigmaLuminance, size, ivec2(0), size, ivec2(0)};
    AtrousProbeRun result;
    result.ms = 1e30;
    size_t out1Offset = 0;
    for (int run = 0; run < std::max(runs, 1); ++run) {
        CommandRecorder rec(context_, &timestamps_);
        rec.BeginPass("atrous");
        rec.Dispatch(pipelines_[unitWeights ? 1 : 0], sets_[unitWeights ? 1 : 0], &push, sizeof(push),
                     AtrousBlockGroups(width_, height_, step_));
        rec.Barrier();
        rec.EndPass();
        out1Offset = rec.Download(out_[0], 16 * n, staging_, 0);
        rec.Download(out_[1], 16 * n, staging_, out1Offset);
        rec.Barrier();
        const auto t0 = std::chrono::steady_clock::now();
        rec.Submit();
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        if (timestamps_.enabled()) ms = timestamps_.Results().at(0).second;
        result.ms = std::min(result.ms, ms);
    }
    result.out0.resize(n);
    result.out1.resize(n);
    std::memcpy(result.out0.data(), staging_.mapped(), 16 * n);
    std::memcpy(result.out1.data(), static_cast<const char*>(staging_.mapped()) + out1Offset, 16 * n);
    return result;
}

AtrousFloor MeasureAtrousFloor(VulkanContext& context, int width, int height, int runs) {
    AtrousFloor f;
    f.width = width;
    f.height = height;
    AtrousProbe probe(context, MakeAtrousProbeImage(width, height, 7), f.step);
    // Alternate the two so that a drifting machine affects both alike; keep each one's best.
    f.fullMs = f.unitWeightsMs = 1e30;
    for (int r = 0; r < std::max(runs, 1); ++r) {
        f.fullMs = std::min(f.fullMs, probe.Run(false, 2).ms);
        f.unitWeightsMs = std::min(f.unitWeightsMs, probe.Run(true, 2).ms);
    }
    for (const PassBytes& pb : SvgfPassBytes(width, height, DenoiserParams{}))
        if (pb.pass == "atrous1") f.bytesPerPixel = pb.bytesPerPixel;
    return f;
}

}  // namespace fovrt
