// Creating denoisers by name (DenoiserNames(): svgf, svgf-weighted, asvgf, two-history,
// two-history-asvgf, each also with a demodulation suffix: "svgf+brdf", denoise/variants.h) on a device: "cpu" (C++ reference), "auto" (Vulkan when a device exists,
// else the reference with a one-line notice), "vulkan" or a Vulkan device index.
#pragma once

#include <memory>
#include <string>

#include "denoise/denoiser.h"
#include "denoise/params.h"
#include "denoise/variants.h"

namespace fovrt {

class VulkanContext;

// `context`: an existing Vulkan context to run on (shared by both eyes; e.g. one wrapping an
// OpenXR session's device); it must outlive the denoiser. Null: the denoiser creates its own
// (per `device`). Unknown names → fovrt::Error listing DenoiserNames().
std::unique_ptr<Denoiser> CreateDenoiser(const std::string& name, const std::string& device,
                                         const DenoiserParams& params, VulkanContext* context = nullptr);

// Parameters a name implies (svgf-weighted sets svgf.weightBySampleCount).
DenoiserParams ParamsForDenoiser(const std::string& name, DenoiserParams params);

// Where a denoiser runs, as far as denoise.precision = auto cares.
struct PrecisionTarget {
    bool vulkan = false;     // false: the C++ reference
    bool cpuDevice = false;  // a Vulkan device of type cpu (lavapipe)
    bool storage16 = false;  // it has storageBuffer16BitAccess
};
PrecisionTarget PrecisionTargetOf(const VulkanContext* context);  // null: the C++ reference
// The target a run with denoise.device = `device` gets, without creating a context (memory plans
// and budgets before anything is allocated).
PrecisionTarget PlannedPrecisionTarget(const std::string& device);
// `requested` unless it is auto. Auto: fp16 storage for the SVGF family on a Vulkan GPU with 16-bit
// storage (half the bytes; its passes are bound by memory traffic there, and fp16 moves the
// thesis protocol's foveal error by at most 0.04 %, docs/performance.md); fp32 on a CPU device
// (lavapipe runs 16-bit loads and stores lane by lane: measured slower there), on a device
// without 16-bit storage, for the C++ reference (it would only emulate the rounding) and for the
// RAE (no comparison covers its fp16 activations).
Precision ResolvePrecision(Precision requested, const DenoiserVariant& variant, const PrecisionTarget& target);
// ParamsForDenoiser with the precision resolved for `target`.
DenoiserParams ParamsForDenoiser(const std::string& name, DenoiserParams params, const PrecisionTarget& target);

}  // namespace fovrt
