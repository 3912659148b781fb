#include "app/report_collect.h"

#include "metrics/error_maps.h"

namespace fovrt {

std::vector<uint8_t> InstancesWithMaterialMaps(const Scene& scene) {
    std::vector<uint8_t> out(scene.instances.size(), 0);
    for (size_t i = 0; i < scene.instances.size(); ++i)
        for (uint32_t m : scene.meshes[scene.instances[i].mesh].materials) {
            const Material& material = scene.materials[m];
            if (material.roughnessTexture >= 0 || material.metallicTexture >= 0 ||
                material.metallicRoughnessTexture >= 0)
                out[i] = 1;
        }
    return out;
}

Plane<uint8_t> DetailMask(const std::vector<uint8_t>& detailInstances, const FrameInputs& inputs) {
    Plane<uint8_t> detail(inputs.objectId.width(), inputs.objectId.height(), uint8_t(0));
    for (size_t p = 0; p < detail.size(); ++p) {
        const uint32_t id = inputs.objectId[p];
        detail[p] = id < detailInstances.size() ? detailInstances[id] : uint8_t(0);
    }
    return detail;
}

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
