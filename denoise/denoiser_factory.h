// Creating denoisers by name (DenoiserNames(): svgf, svgf-weighted, asvgf, two-history,
// two-history-asvgf, each also with a demodulation suffix: "svgf+brdf", denoise/variants.h) on a device: "cpu" (C++ reference), "auto" (Vulkan when a device exists,
// else the reference with a one-line notice), "vulkan" or a Vulkan device index.
#pragma once

#include <memory>
#include <string>

#include "denoise/denoiser.h"
#include "denoise/params.h"

namespace fovrt {

class VulkanContext;

// `context`: an existing Vulkan context to run on (shared by both eyes; e.g. one wrapping an
// OpenXR session's device); it must outlive the denoiser. Null: the denoiser creates its own
// (per `device`). Unknown names → fovrt::Error listing DenoiserNames().
std::unique_ptr<Denoiser> CreateDenoiser(const std::string& name, const std::string& device,
                                         const DenoiserParams& params, VulkanContext* context = nullptr);

// Parameters a name implies (svgf-weighted sets svgf.weightBySampleCount).
DenoiserParams ParamsForDenoiser(const std::string& name, DenoiserParams params);

}  // namespace fovrt
