// MetricsCollector: the experiment loop's one call per (scene, frame, eye). It builds the region
// masks from the eye camera and gaze, computes every metric map of every variant against the
// reference (FLIP at the eye's pixels per degree), averages them per region and appends the rows
// to Results. It keeps each variant's previous output per (scene, eye) for the temporal error.
#pragma once

#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "app/report.h"
#include "core/camera.h"
#include "core/frame_inputs.h"
#include "core/image.h"
#include "metrics/regions.h"
#include "scene/scene.h"

namespace fovrt {

struct EyeFrameImages {
    std::string scene;
    uint32_t seed = 1;  // the run seed of the frame
    int frame = 0;
    int eye = 0;
    EyeCamera camera;
    vec3 gazeEye{0.0f, 0.0f, -1.0f};  // gaze direction in eye space
    FoveaRadius fovea;                 // default: the thesis's 200 px spp disc
    bool cameraCut = false;            // no temporal error across a cut
    const Plane<vec3>* reference = nullptr;
    const Plane<uint8_t>* detailMask = nullptr;  // region "detail" when set and not empty
    std::vector<std::pair<std::string, const Plane<vec3>*>> outputs;  // variant -> HDR output
};

// Per instance: 1 when a material of its mesh has a roughness or metallic map (scene-file maps
// or glTF metallic-roughness): the "detail" region of brdf-demodulation experiments.
std::vector<uint8_t> InstancesWithMaterialMaps(const Scene& scene);
// The "detail" mask of one eye's frame: the pixels whose primary hit is such an instance.
Plane<uint8_t> DetailMask(const std::vector<uint8_t>& detailInstances, const FrameInputs& inputs);

class MetricsCollector {
public:
    explicit MetricsCollector(Results& results) : results_(results) {}

    // Appends one row per (variant, non-empty region, metric). Returns the region set it used.
    RegionSet Add(const EyeFrameImages& images);

private:
    Results& results_;
    std::map<std::tuple<std::string, int, std::string>, Plane<vec3>> previous_;  // (scene, eye, variant)
};

}  // namespace fovrt
