// DenoiserSet: every configured denoiser variant, one instance per eye (histories are per eye),
// all on one shared Vulkan context (or the C++ reference when device = cpu / no device).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/config.h"
#include "denoise/denoiser.h"
#include "vk/context.h"

namespace fovrt {

// The denoise config a run gives its denoisers: config.denoise with
// params.sampleCountsMayBeZero set where the run's foveation may put 0 in the spp map
// (MapMayHaveZeroSamples), so that every SVGF-family variant keeps a pixel without a path sample.
// Every command that renders, or plans a run's memory, builds its denoisers from it.
DenoiseConfig RunDenoiseConfig(const RunConfig& config);

// The parameters variant `name` of a run gets: RunDenoiseConfig's, with denoise.precision = auto
// resolved for the device denoise.device names (ResolvePrecision), as CreateDenoiser resolves it.
DenoiserParams RunDenoiserParams(const RunConfig& config, const std::string& name);

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
    // The variants' storage: "fp16", or "fp16 (rae: fp32)" where they differ.
    std::string StorageDescription() const;
    const VulkanContext* Context() const { return context_ ? &*context_ : nullptr; }

private:
    struct Variant {
        std::string name;
        Precision precision = Precision::Fp32;
        std::array<std::unique_ptr<Denoiser>, 2> eyes;
    };
    std::optional<VulkanContext> context_;
    std::vector<Variant> variants_;
};

// Every large buffer a run allocates for two eyes at W×H, computed without allocating any: all
// variants' denoiser buffers (their memory plans), FrameInputs, spp maps, the renderer's
// visibility buffers and, with run.score, the metric's frames (PlanVdpMemory) (for
// --memory-budget, checked before anything is allocated).
std::vector<BufferPlan> PlanRunMemory(const RunConfig& config);
// The luminance frames FovVideoVDP holds until a sequence ends (app/experiment_vdp.h), for each
// of `eyes` eyes: the reference's and each variant's, 4 bytes per pixel per frame of run.frames.
// Empty when nothing is scored: metric.vdp off, or a `run` without run.score (`experiment` passes true).
std::vector<BufferPlan> PlanVdpMemory(const RunConfig& config, bool scored, int eyes = 2);
// Throws fovrt::Error when PlanRunMemory exceeds config.memoryBudget (0 = none), naming command
// `what`: called by every command that renders before it allocates anything large.
void EnforceRunBudget(const RunConfig& config, const std::string& what);
// The reference images in flight, one HDR image per eye (`fovrt reference`; an experiment holds
// them beside PlanRunMemory's buffers).
std::vector<BufferPlan> PlanReferenceMemory(const RunConfig& config);

// Turns a std::bad_alloc of command `what` into one line (fovrt::Error) naming the resolution
// and the bytes its memory plan asks for.
[[noreturn]] void FailOutOfMemory(const RunConfig& config, const std::vector<BufferPlan>& plan,
                                  const std::string& what);

}  // namespace fovrt
