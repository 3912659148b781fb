#include "denoise/denoiser_factory.h"

#include <cstdio>

#include <fmt/format.h>

#include "core/error.h"
#include "denoise/memory_plan.h"
#include "denoise/reference/svgf_cpu.h"
#include "denoise/vulkan/svgf_vk.h"
#include "denoise/reference/two_history_ref.h"
#include "denoise/vulkan/two_history_vk.h"
#include "denoise/variants.h"
#include "vk/context.h"
#include "vk/device_choice.h"

namespace fovrt {

namespace {

bool IsSvgf(const std::string& name) { return FindDenoiserVariant(name).family == DenoiserFamily::Svgf; }

void CheckName(const std::string& name) { FindDenoiserVariant(name); }

// The caller's context (not owned), or a new one on the device the setting resolves to
// (vk/device_choice.h); null → the C++ reference.
std::shared_ptr<VulkanContext> ResolveContext(const std::string& device, VulkanContext* context) {
    if (context) return std::shared_ptr<VulkanContext>(context, [](VulkanContext*) {});
    const DeviceDecision decision = ResolveVulkanDevice(device);
    if (!decision.vulkan) {
        if (!decision.notice.empty()) std::fprintf(stderr, "%s\n", decision.notice.c_str());
        return nullptr;
    }
    return std::make_shared<VulkanContext>(VulkanContext::Create(decision.options));
}

}  // namespace

DenoiserParams ParamsForDenoiser(const std::string& name, DenoiserParams params) {
    return ParamsForVariant(FindDenoiserVariant(name), params);
}

std::unique_ptr<Denoiser> CreateDenoiser(const std::string& name, const std::string& device,
                                         const DenoiserParams& params, VulkanContext* context) {
    CheckName(name);
    const DenoiserParams p = ParamsForDenoiser(name, params);
    const bool cpu = device == "cpu" && !context;
    if (IsSvgf(name)) {
        if (cpu) return std::make_unique<SvgfReferenceDenoiser>(name, p);
        auto ctx = ResolveContext(device, context);
        if (!ctx) return std::make_unique<SvgfReferenceDenoiser>(name, p);
        return std::make_unique<SvgfVulkanDenoiser>(name, std::move(ctx), p);
    }
    // Denoisers of other modules register here (two-history, asvgf, two-history-asvgf).
    if (TwoHistoryVariant v; TwoHistoryVariantOf(name, v)) {
        if (cpu) return CreateTwoHistoryCpuDenoiser(v, p);
        auto ctx = ResolveContext(device, context);
        if (!ctx) return CreateTwoHistoryCpuDenoiser(v, p);
        return std::make_unique<TwoHistoryVulkanDenoiser>(v, std::move(ctx), p);
    }
    Fail("denoiser '{}' is not implemented yet", name);
}

}  // namespace fovrt
