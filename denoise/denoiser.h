// Denoiser: reconstruction of one eye's noisy FrameInputs into an HDR image (the methods and
// their papers: docs/algorithms.md, docs/papers.bib).
// Each eye owns its own Denoiser (histories are per eye). Implementations come in two backends
// with the same maths: Vulkan compute (shaders/) and the plain C++ reference (denoise/*_ref.cpp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/frame_inputs.h"
#include "core/image.h"
#include "denoise/debug_views.h"
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
    bool transient = false; // a slot of the transient pool: planes that live only within a frame,
                            // at times that do not overlap (else a plane's own buffer)
    bool shared = false;    // one buffer of this name per device, which every denoiser's frame
                            // uses in turn (the transient pool's slots, the staging ring:
                            // vk/shared_buffers.h); its size is the largest user's
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

    // Debug views (denoise/debug_views.h): the internal per-pixel planes this variant offers, by
    // name, in table order (e.g. {"historyLength", "alpha", "lambda"} for asvgf); the same on both
    // backends. Empty when Name() is not a variant of the table.
    std::vector<std::string> DebugViews() const;
    // Copies view `name` of the last Denoise() call into `out` (W×H, one float per pixel; fp16
    // history storage read back as float). Returns false, leaving `out` untouched, for a name
    // DebugViews() does not list, or when no frame was denoised since construction or the last
    // Reset(). On Vulkan a synchronous read-back (debug speed); nothing is done per frame for it.
    bool ReadDebugView(const std::string& name, Plane<float>& out);

private:
    // The plane of `view`, one DebugViews() lists, of the last Denoise(); false (and `out`
    // untouched) when there was none since construction or Reset().
    virtual bool ReadDebugPlane(DebugViewId view, Plane<float>& out) = 0;
};

// Every buffer the named denoiser allocates at W×H for one eye.
std::vector<BufferPlan> PlanDenoiserMemory(const std::string& name, int width, int height,
                                           const DenoiserParams& params);
// Adds one denoiser's allocations to those of a device that runs several (both eyes, every
// variant): its own buffers as `prefix` + name, and each shared one (BufferPlan::shared: the
// transient pool's slots, the staging ring) once per device as "shared." + name, as large as its
// largest user's, since their frames take turns with them (vk/shared_buffers.h).
void AddDenoiserOnDevice(std::vector<BufferPlan>& device, const std::string& prefix,
                         const std::vector<BufferPlan>& denoiser);

}  // namespace fovrt
