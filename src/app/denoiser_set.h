// DenoiserSet: every configured denoiser variant, one instance per eye (histories are per eye),
// all on one shared Vulkan context (or the C++ reference when device = cpu / no device).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/config.h"
#include "denoise/denoiser.h"
#include "vk/context.h"

namespace fovrt {

class DenoiserSet {
public:
    explicit DenoiserSet(const DenoiseConfig& config);

    size_t size() const { return variants_.size(); }
    const std::string& Name(size_t variant) const { return variants_[variant].name; }
    Denoiser& At(size_t variant, int eye) { return *variants_[variant].eyes[size_t(eye)]; }
    // Drops every history of every variant and eye: the next frame is denoised as by a fresh set
    // (an experiment's next run seed), without re-creating the pipelines.
    void Reset();
    // "vulkan (<device name>)" or "cpu (C++ reference)".
    std::string DeviceDescription() const;
    const VulkanContext* Context() const { return context_ ? &*context_ : nullptr; }

private:
    struct Variant {
        std::string name;
        std::array<std::unique_ptr<Denoiser>, 2> eyes;
    };
    std::optional<VulkanContext> context_;
    std::vector<Variant> variants_;
};

// Every buffer all variants allocate for two eyes at W×H (for --memory-budget and manifests).
std::vector<BufferPlan> PlanRunMemory(const RunConfig& config);

}  // namespace fovrt
