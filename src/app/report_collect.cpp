#include "app/report_collect.h"

#include "metrics/error_maps.h"

namespace fovrt {

RegionSet MetricsCollector::Add(const EyeFrameImages& images) {
    FOVRT_CHECK(images.reference != nullptr);
    RegionSet regions = RegionSet::Build(images.camera, images.gazeEye, images.fovea);
    if (images.detailMask) regions.AddMask("detail", *images.detailMask);
    MetricOptions options;
    options.pixelsPerDegree = images.camera.PixelsPerDegree();
    options.relMseEpsilon = float(results_.relMseEpsilon);
    for (const auto& [variant, output] : images.outputs) {
        FOVRT_CHECK(output != nullptr);
        const auto key = std::make_tuple(images.scene, images.eye, variant);
        auto prev = previous_.find(key);
        const bool hasPrevious = prev != previous_.end() && !images.cameraCut &&
                                 prev->second.width() == output->width() && prev->second.height() == output->height();
        ErrorMaps maps = ComputeErrorMaps(*output, *images.reference, options, hasPrevious ? &prev->second : nullptr);
        for (const RegionValue& v : MeanOverRegions(maps, regions))
            results_.Add({images.scene, images.frame, images.eye, variant, v.region, v.metric, v.value, images.seed});
        previous_[key] = *output;
    }
    return regions;
}

}  // namespace fovrt
