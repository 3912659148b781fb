#include "pipeline/denoiser_set.h"

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

#include "core/error.h"
#include "denoise/denoiser_factory.h"
#include "denoise/memory_plan.h"
#include "denoise/variants.h"
#include "foveation/spp_model.h"
#include "render/visibility_buffer.h"
#include "vk/device_choice.h"

namespace fovrt {

DenoiseConfig RunDenoiseConfig(const RunConfig& config) {
    DenoiseConfig denoise = config.denoise;
    denoise.params.sampleCountsMayBeZero = MapMayHaveZeroSamples(config.foveation);
    return denoise;
}

DenoiserParams RunDenoiserParams(const RunConfig& config, const std::string& name) {
    const DenoiseConfig denoise = RunDenoiseConfig(config);
    const PrecisionTarget target = denoise.params.precision == Precision::Auto
                                       ? PlannedPrecisionTarget(config.denoise.device)
                                       : PrecisionTarget{};
    return ParamsForDenoiser(name, denoise.params, target);
}

DenoiserSet::DenoiserSet(const DenoiseConfig& config) {
    if (!config.denoisers.empty()) {
        const DeviceDecision decision = ResolveVulkanDevice(config.device);
        if (decision.vulkan)
            context_.emplace(VulkanContext::Create(decision.options));
        else if (!decision.notice.empty())
            std::fprintf(stderr, "%s\n", decision.notice.c_str());
    }
    std::string device = context_ ? config.device : "cpu";
    for (const std::string& name : config.denoisers) {
        Variant variant;
        variant.name = name;
        variant.precision = ResolvePrecision(config.params.precision, FindDenoiserVariant(name),
                                             PrecisionTargetOf(context_ ? &*context_ : nullptr));
        for (auto& eye : variant.eyes)
            eye = CreateDenoiser(name, device, config.params, context_ ? &*context_ : nullptr);
        variants_.push_back(std::move(variant));
    }
}

void DenoiserSet::Reset() {
    for (Variant& variant : variants_)
        for (auto& eye : variant.eyes) eye->Reset();
}

std::string DenoiserSet::DeviceDescription() const {
    if (context_) return "vulkan (" + context_->deviceName() + ")";
    return "cpu (C++ reference)";
}

std::string DenoiserSet::StorageDescription() const {
    if (variants_.empty()) return "";
    const Precision first = variants_.front().precision;
    std::string others;
    for (const Variant& v : variants_)
        if (v.precision != first) others += (others.empty() ? "" : ", ") + v.name;
    if (others.empty()) return PrecisionName(first);
    const Precision other = first == Precision::Fp16 ? Precision::Fp32 : Precision::Fp16;
    return fmt::format("{} ({}: {})", PrecisionName(first), others, PrecisionName(other));
}

namespace {

// Bytes per pixel of a plane list (core/plane_list.h), from its rows' element types: what
// allocating it at W×H takes, known without allocating it.
#define FOVRT_PLANE_PIXEL_BYTES(member, Type, neutral, channels, doc) +sizeof(Type)
constexpr size_t kFrameInputsPixelBytes = 0 FOVRT_FRAME_INPUT_PLANES(FOVRT_PLANE_PIXEL_BYTES);
constexpr size_t kVisibilityPixelBytes = 0 FOVRT_VISIBILITY_PLANES(FOVRT_PLANE_PIXEL_BYTES);
#undef FOVRT_PLANE_PIXEL_BYTES

}  // namespace

std::vector<BufferPlan> PlanRunMemory(const RunConfig& config) {
    const size_t pixels = size_t(config.camera.width) * size_t(config.camera.height);
    const DenoiseConfig denoise = RunDenoiseConfig(config);
    std::vector<BufferPlan> plan;
    // Every variant of both eyes on one device: the shared transient pool and staging ring once.
    for (const std::string& name : denoise.denoisers) {
        const std::vector<BufferPlan> denoiser =
            PlanDenoiserMemory(name, config.camera.width, config.camera.height, RunDenoiserParams(config, name));
        for (int eye = 0; eye < 2; ++eye)
            AddDenoiserOnDevice(plan, name + ".eye" + std::to_string(eye) + ".", denoiser);
    }
    // The frame pipeline's own planes, per eye: FrameInputs, the spp map, and the renderer's
    // visibility buffer (two with A-SVGF gradient samples: their forward projection reads the
    // previous frame's). Counted from the plane lists, so nothing is allocated to count them.
    const RendererNeeds needs = RendererNeedsOf(config.denoise.denoisers, "denoise.denoisers");
    const size_t visibilityBuffers = needs.gradientSamples ? 2 : 1;
    for (int eye = 0; eye < 2; ++eye) {
        const std::string prefix = "eye" + std::to_string(eye) + ".";
        plan.push_back({prefix + "frame_inputs", pixels * kFrameInputsPixelBytes, false});
        plan.push_back({prefix + "spp_map", pixels * sizeof(uint16_t), false});
        plan.push_back({prefix + "render.visibility",
                        visibilityBuffers * pixels * kVisibilityPixelBytes, false});
    }
    for (BufferPlan& vdp : PlanVdpMemory(config, config.run.score)) plan.push_back(std::move(vdp));
    return plan;
}

std::vector<BufferPlan> PlanVdpMemory(const RunConfig& config, bool scored, int eyes) {
    if (!scored || !config.metric.vdp) return {};
    const size_t bytes = size_t(config.camera.width) * size_t(config.camera.height) * sizeof(float) *
                         size_t(std::max(1, config.run.frames));
    std::vector<BufferPlan> plan;
    for (int eye = 0; eye < eyes; ++eye) {
        const std::string prefix = "eye" + std::to_string(eye) + ".vdp.";
        plan.push_back({prefix + "reference_luminance", bytes, false});
        for (const std::string& name : config.denoise.denoisers)
            plan.push_back({prefix + name + "_luminance", bytes, false});
    }
    return plan;
}

void EnforceRunBudget(const RunConfig& config, const std::string& what) {
    EnforceMemoryBudget(PlanRunMemory(config), config.memoryBudget, what);
}

[[noreturn]] void FailOutOfMemory(const RunConfig& config, const std::vector<BufferPlan>& plan,
                                  const std::string& what) {
    const size_t total = TotalBytes(plan);
    Fail("out of memory: {} at {}x{} per eye asked for {} bytes ({:.1f} MiB) and an allocation failed "
         "(lower camera.width / camera.height, or give --memory-budget to refuse before rendering)",
         what, config.camera.width, config.camera.height, total, double(total) / 1048576.0);
}

std::vector<BufferPlan> PlanReferenceMemory(const RunConfig& config) {
    const size_t imageBytes = size_t(config.camera.width) * size_t(config.camera.height) * sizeof(vec3);
    return {{"reference.image.eye0", imageBytes, false}, {"reference.image.eye1", imageBytes, false}};
}

}  // namespace fovrt
