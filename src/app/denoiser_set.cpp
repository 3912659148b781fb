#include "app/denoiser_set.h"

#include <cstdio>

#include "denoise/denoiser_factory.h"
#include "vk/device_choice.h"

namespace fovrt {

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

std::vector<BufferPlan> PlanRunMemory(const RunConfig& config) {
    std::vector<BufferPlan> plan;
    for (const std::string& name : config.denoise.denoisers) {
        for (int eye = 0; eye < 2; ++eye) {
            for (BufferPlan buffer : PlanDenoiserMemory(name, config.camera.width,
                                                        config.camera.height,
                                                        ParamsForDenoiser(name, config.denoise.params))) {
                buffer.name = name + ".eye" + std::to_string(eye) + "." + buffer.name;
                plan.push_back(std::move(buffer));
            }
        }
    }
    return plan;
}

}  // namespace fovrt
