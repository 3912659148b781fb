// The display FovVideoVDP (metrics/fovvideovdp.h) scores a run's frames on, from its [metric]
// settings and an eye camera: the same for `fovrt experiment`, `fovrt run --score` and the live
// sessions' vdp view.
//
// [metric] in config/config.h:
//   - geometry: the eye camera's own pixel (its horizontal FOV over its width, so pixels per
//     degree follow the headset's optics), or a named profile's / metric.ppd;
//   - photometry: the frames as the PNGs show them: linear radiance × 2^output.exposure,
//     clamped to [0, 1] and mapped linearly to [black, peak] (peak 100 cd/m² unless the profile or
//     metric.peak says otherwise). fovrt's radiance has no absolute scale (a scene's emitters are
//     in arbitrary units), so "absolute" input would be a guess; the display's white is not.
#pragma once

#include <string>

#include "config/config.h"
#include "core/camera.h"
#include "core/image.h"
#include "metrics/fovvideovdp.h"

namespace fovrt {

// The display a run's frames are scored on (config.metric, an eye camera).
struct VdpExperimentDisplay {
    std::string name;  // metric.display
    VdpPhotometry photometry;
    VdpGeometry geometry;
};
VdpExperimentDisplay ExperimentVdpDisplay(const RunConfig& config, const EyeCamera& camera);

// The luminance (cd/m²) the display emits for linear radiance shown at the PNGs' exposure.
Plane<float> VdpDisplayLuminance(const Plane<vec3>& radiance, float exposureStops, const VdpPhotometry& photometry);

// The metric's fixation for a gaze position in continuous pixel coordinates (EyeFrame's
// trueGazePixel: pixel x spans [x, x+1)); the metric adds the half pixel itself.
VdpFixation VdpFixationAt(const vec2& gazePixel);

}  // namespace fovrt
