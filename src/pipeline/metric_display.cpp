#include "pipeline/metric_display.h"

#include <cmath>

#include "core/error.h"

namespace fovrt {

VdpExperimentDisplay ExperimentVdpDisplay(const RunConfig& config, const EyeCamera& camera) {
    const MetricConfig& m = config.metric;
    VdpExperimentDisplay d;
    d.name = m.display;
    if (m.display == "camera") {
        // The eye's own pixel: its horizontal extent (tan right − tan left) over its width.
        const Fov& fov = camera.fov();
        d.geometry.tanPerPixel =
            (std::tan(double(fov.angleRight)) - std::tan(double(fov.angleLeft))) / double(camera.width());
    } else {
        const VdpDisplay& profile = FindVdpDisplay(m.display);
        d.photometry = profile.photometry;
        d.geometry = profile.geometry;
    }
    // Display-referred, as the PNGs show the frames (see the header).
    d.photometry.eotf = VdpEotf::Linear;
    if (m.ppd > 0.0f) d.geometry = VdpGeometry::FromPixelsPerDegree(double(m.ppd));
    if (m.peak > 0.0f) d.photometry.peak = double(m.peak);
    if (d.photometry.black >= d.photometry.peak)
        Fail("metric.peak: {} cd/m² is not above the display's black level {} cd/m²", d.photometry.peak,
             d.photometry.black);
    return d;
}

VdpFixation VdpFixationAt(const vec2& gazePixel) { return {gazePixel.x - 0.5f, gazePixel.y - 0.5f}; }

Plane<float> VdpDisplayLuminance(const Plane<vec3>& radiance, float exposureStops, const VdpPhotometry& photometry) {
    const float scale = std::exp2(exposureStops);
    if (scale == 1.0f) return VdpLuminance(radiance, photometry);
    Plane<vec3> exposed(radiance.width(), radiance.height());
    for (size_t i = 0; i < radiance.size(); ++i) exposed[i] = radiance[i] * scale;
    return VdpLuminance(exposed, photometry);
}

}  // namespace fovrt
