// Probes into the path tracer for tests and `fovrt bench`, kept out of the rendering interface
// (renderer.h). A probe renderer is the same tracer instantiated over a recording scene
// (render/recording_scene.h): its rays can be logged, while the production renderer's ray calls
// go straight to Embree with nothing per ray. Both render bit-identical frames
// (tests/render_probes_test.cpp).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/camera.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace fovrt {

// One ray as the tracer handed it to Embree (fovrt bench's bare-traversal probe): closest hit
// along origin + t dir for t in (0, tFar), or, for a shadow ray, any hit.
struct TracedRay {
    vec3 origin;
    vec3 dir;
    float tFar;
    bool shadow;
};

// A Renderer with probes. Obtained only from CreateProbeRenderer; renders exactly as
// CreateRenderer's renderer does.
class ProbeRenderer : public Renderer {
public:
    // Re-shading (A-SVGF's claim, checked by tests): shades `sample` as seen from `camera` in the
    // current frame with n samples whose seeds derive from `seed`, exactly as RenderEye shades a
    // visibility-buffer entry (ShadePixel). Returns the remodulated colour.
    virtual vec3 Shade(const EyeCamera& camera, const SurfaceSample& sample, uint32_t seed,
                       int sampleCount) const = 0;
    // World position of a surface sample in the current frame (rigid motion applied).
    virtual vec3 WorldPosition(const SurfaceSample& sample) const = 0;

    // Bare-traversal probe (fovrt bench): while `log` is set, every ray traced is appended to it
    // (slowly, under a lock: for one probe frame); nullptr stops. TraceBare traces `rays` again
    // with nothing but rtcIntersect1 / rtcOccluded1, one ray at a time, on the renderer's
    // threads, and returns how many hit (so the work cannot be skipped).
    virtual void RecordRays(std::vector<TracedRay>* log) = 0;
    virtual uint64_t TraceBare(const std::vector<TracedRay>& rays) const = 0;
};

std::unique_ptr<ProbeRenderer> CreateProbeRenderer(const Scene& scene, const RenderSettings& settings);

}  // namespace fovrt
