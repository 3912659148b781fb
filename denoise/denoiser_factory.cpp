#include "denoise/denoiser_factory.h"

#include <cstdio>
#include <map>
#include <mutex>

#include <fmt/format.h>

#include "core/error.h"
#include "denoise/demodulation.h"
#include "denoise/memory_plan.h"
#include "denoise/reference/rae_cpu.h"
#include "denoise/reference/svgf_family_ref.h"
#include "denoise/vulkan/rae_vk.h"
#include "denoise/vulkan/svgf_family_vk.h"
#include "denoise/variants.h"
#include "vk/context.h"
#include "vk/device_choice.h"

namespace fovrt {

namespace {


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

PrecisionTarget PrecisionTargetOf(const VulkanContext* context) {
    if (!context) return {};
    return {true, context->isCpuDevice(), context->supports16BitStorage()};
}

PrecisionTarget PlannedPrecisionTarget(const std::string& device) {
    // Listing the devices creates an instance (a fifth of a second on lavapipe); every variant's
    // plan asks, and the devices do not change while the process runs.
    static std::mutex mutex;
    static std::map<std::string, PrecisionTarget> known;
    std::lock_guard<std::mutex> lock(mutex);
    if (auto it = known.find(device); it != known.end()) return it->second;
    const std::vector<VulkanDeviceInfo> devices = VulkanContext::ListDevices();
    const DeviceDecision decision = ResolveVulkanDevice(device, devices);
    PrecisionTarget target;
    for (const VulkanDeviceInfo& d : devices)
        if (decision.vulkan && d.index == decision.index) target = {true, d.type == "cpu", d.storage16};
    known[device] = target;
    return target;
}

Precision ResolvePrecision(Precision requested, const DenoiserVariant& variant, const PrecisionTarget& target) {
    if (requested != Precision::Auto) return requested;
    const bool gpu16 = target.vulkan && !target.cpuDevice && target.storage16;
    return gpu16 && variant.family != DenoiserFamily::Rae ? Precision::Fp16 : Precision::Fp32;
}

DenoiserParams ParamsForDenoiser(const std::string& name, DenoiserParams params, const PrecisionTarget& target) {
    const DenoiserVariant& variant = FindDenoiserVariant(name);
    params.precision = ResolvePrecision(params.precision, variant, target);
    return ParamsForVariant(variant, params);
}

std::unique_ptr<Denoiser> CreateDenoiser(const std::string& name, const std::string& device,
                                         const DenoiserParams& params, VulkanContext* context) {
    const DenoiserVariant& v = FindDenoiserVariant(name);
    // A demodulation suffix wraps the variant's host in the shared re-demodulation step.
    if (std::optional<Demodulation> want = DenoiserDemodulation(name))
        return WithDemodulation(CreateDenoiser(std::string(v.name), device, params, context), *want, name);
    // The family picks the host; the row's flags pick the passes of its plan.
    std::shared_ptr<VulkanContext> ctx = device == "cpu" && !context ? nullptr : ResolveContext(device, context);
    const DenoiserParams p = ParamsForDenoiser(std::string(v.name), params, PrecisionTargetOf(ctx.get()));
    if (v.family == DenoiserFamily::Rae) {
        std::unique_ptr<Denoiser> rae;
        if (ctx) rae = std::make_unique<RaeVulkanDenoiser>(name, std::move(ctx), p);
        else rae = std::make_unique<RaeReferenceDenoiser>(name, p);
        // Its features and remodulation are the albedo's (Chaitanya et al. 2017, §3.2) whatever
        // render.demodulation the frame was traced with (a no-op on albedo-demodulated frames).
        return WithDemodulation(std::move(rae), Demodulation::Albedo, name);
    }
    // svgf, svgf-weighted, asvgf, two-history, two-history-asvgf: one host per backend runs the
    // row's pass plan.
    if (!ctx) return std::make_unique<SvgfFamilyReferenceDenoiser>(v, p);
    return std::make_unique<SvgfFamilyVulkanDenoiser>(v, std::move(ctx), p);
}

}  // namespace fovrt
