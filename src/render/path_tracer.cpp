// The stereo Embree path tracer behind Renderer (renderer.h): PathTracer (path_tracer.h) over
// EmbreeScene, so no ray call of the production tracer passes through probe code. The tracer is
// split by job, as pbrt-v4 splits lightsamplers, cameras and integrators (internal headers):
//   path_tracer.h         PathTracer: SetFrame, RenderEye (tiles, A-SVGF merge, history), Stats
//   integrator.h          path vertices (Advance / Land / Finish) -> ShadePixel (n samples)
//   light_sampler.h       lights: emitter power distribution, NEE and its MIS weights
//   camera_rays.h         the pinhole eye's primary rays and depth gradients
//   tiles.h               16×16 tiles in parallel: TraceTile / ShadeTile -> ShadeEntry
//   forward_projection.h  A-SVGF's gradient samples merged into the visibility buffer
//   reference.h           the high-spp reference
// The probe renderer (probes.h) is the same template over a RecordingScene, compiled in its own
// translation unit (probe_renderer.cpp, CMakeLists.txt).
#include <memory>

#include "render/path_tracer.h"

namespace fovrt {

std::unique_ptr<Renderer> CreateRenderer(const Scene& scene, const RenderSettings& settings) {
    return std::make_unique<PathTracer<const EmbreeScene&, Renderer>>(scene, settings);
}

}  // namespace fovrt
