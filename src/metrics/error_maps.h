// Everything fovrt measures about one (frame, eye, variant) image: the per-pixel maps, computed
// once, and their means over every region of a RegionSet.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "metrics/regions.h"

namespace fovrt {

struct ErrorMaps {
    Plane<float> relMse;                  // per pixel, mean over RGB, ε = kRelMseEpsilon
    Plane<float> ssim;                    // per pixel, on tonemapped luma
    Plane<float> flip;                    // per pixel, LDR-FLIP
    std::optional<Plane<float>> temporal; // |Δ lum| to the previous frame of the same variant
};

struct MetricOptions {
    float pixelsPerDegree = 0.0f;  // for FLIP; <= 0 skips FLIP
    float relMseEpsilon = 0.01f;
};

// previous: the same variant's output of the previous frame, or nullptr (no temporal map).
ErrorMaps ComputeErrorMaps(const Plane<vec3>& test, const Plane<vec3>& reference, const MetricOptions& options,
                           const Plane<vec3>* previous = nullptr);

struct RegionValue {
    std::string region;
    std::string metric;  // "relmse", "ssim", "flip", "temporal"
    double value = 0.0;
};

// Means of every map over every non-empty region, in region order then metric order.
std::vector<RegionValue> MeanOverRegions(const ErrorMaps& maps, const RegionSet& regions);

}  // namespace fovrt
