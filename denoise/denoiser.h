// Denoiser: reconstruction of one eye's noisy FrameInputs into an HDR image (SPEC §3–§5).
// Each eye owns its own Denoiser (histories are per eye). Implementations come in two backends
// with the same maths: Vulkan compute (shaders/) and the plain C++ reference (denoise/*_ref.cpp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/frame_inputs.h"
#include "core/image.h"
#include "denoise/params.h"
#include "denoise/variants.h"

namespace fovrt {

struct PassTiming {
    std::string pass;   // e.g. "reproject", "atrous0"
    double ms = 0.0;
};

// One buffer of a denoiser's memory plan (for `fovrt memory` and --memory-budget).
struct BufferPlan {
    std::string name;
    size_t bytes = 0;
    bool history = false;   // persists across frames (vs. per-frame scratch)
};

struct DenoiseStats {
    uint64_t nonFiniteSamples = 0;  // NaN/Inf inputs replaced before accumulation
    uint64_t negativeSamples = 0;   // negative inputs clamped to 0
};

class Denoiser {
public:
    virtual ~Denoiser() = default;
    virtual std::string Name() const = 0;     // the factory name, e.g. "two-history"
    virtual std::string Backend() const = 0;  // "vulkan" or "cpu"
    // Drops every history (camera cut, resize, scene change, parameter change).
    virtual void Reset() = 0;
    // Denoises one frame; `output` is resized to the input's resolution and holds the remodulated
    // HDR colour albedo * filtered(illumination) + emission.
    virtual void Denoise(const FrameInputs& inputs, Plane<vec3>& output) = 0;
    // Per-pass timings of the last Denoise() call (GPU timestamps on Vulkan, wall clock on CPU).
    virtual std::vector<PassTiming> LastTimings() const = 0;
    virtual DenoiseStats Stats() const = 0;
};

// Every buffer the named denoiser allocates at W×H for one eye.
std::vector<BufferPlan> PlanDenoiserMemory(const std::string& name, int width, int height,
                                           const DenoiserParams& params);


}  // namespace fovrt
