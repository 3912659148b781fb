#include "metrics/error_maps.h"

#include "metrics/flip.h"
#include "metrics/image_metrics.h"

namespace fovrt {

ErrorMaps ComputeErrorMaps(const Plane<vec3>& test, const Plane<vec3>& reference, const MetricOptions& options,
                           const Plane<vec3>* previous) {
    ErrorMaps maps;
    maps.relMse = RelMseMap(test, reference, options.relMseEpsilon);
    maps.ssim = SsimMap(test, reference);
    if (options.pixelsPerDegree > 0.0f) maps.flip = FlipMap(test, reference, options.pixelsPerDegree);
    if (previous) maps.temporal = TemporalErrorMap(test, *previous);
    return maps;
}

std::vector<RegionValue> MeanOverRegions(const ErrorMaps& maps, const RegionSet& regions) {
    std::vector<RegionValue> values;
    for (const Region& r : regions.regions()) {
        if (r.pixelCount == 0) continue;
        values.push_back({r.name, "relmse", MaskedMean(maps.relMse, &r.mask)});
        values.push_back({r.name, "ssim", MaskedMean(maps.ssim, &r.mask)});
        if (!maps.flip.empty()) values.push_back({r.name, "flip", MaskedMean(maps.flip, &r.mask)});
        if (maps.temporal) values.push_back({r.name, "temporal", MaskedMean(*maps.temporal, &r.mask)});
    }
    return values;
}

}  // namespace fovrt
