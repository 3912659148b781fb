// Renderer: the stereo Embree path tracer behind one small interface for rendering (SPEC §2).
// Layers: Advance / Land -> ShadePixel (n from the spp map; render/integrator.h) -> ShadeEntry
// (render/tiles.h) -> RenderEye (render/path_tracer.cpp, which lists the tracer's files). Probes
// for tests and the bench (ray log, re-shading) are a separate interface: render/probes.h.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/camera.h"
#include "core/frame_inputs.h"
#include "core/image.h"
#include "render/visibility_buffer.h"
#include "scene/scene.h"

namespace fovrt {

struct RenderSettings {
    int maxDepth = 2;          // path vertices after the camera: 1 = direct only, 2 = one indirect bounce
    uint32_t seed = 1;         // run seed; per-pixel seeds = PixelSeed(seed, eye, x, y, frame)
    int threads = 0;           // 0: all hardware threads (result is identical for any count)
    bool gradientSamples = false;  // A-SVGF: fill FrameInputs::gradientSamples
    // render.demodulation: what FrameInputs' direct / indirect are divided by (FrameInputs::
    // demodulation records the choice). The albedo plane is always written.
    Demodulation demodulation = Demodulation::Albedo;
    // Fill FrameInputs::fbeta (one table lookup per primary hit) also under albedo demodulation,
    // for "+brdf" variants; under brdf demodulation it is always filled. Off, the plane stays 0.
    bool fbetaPlane = false;
};

// Work counters since the last ResetStats(): rays (primary, shadow, bounce) and every path sample
// taken. Samples whose value was NaN/Inf are dropped (counted, contribute 0). shadowRays counts
// the shadow tests of every sample (one per light sample); those of point/spot/directional lights
// at the primary vertex do not depend on the sample, so they are traced once per pixel and the
// other samples reuse the answer (shadowRaysReused of shadowRays were not traced). guideRays: the
// primary rays (counted in primaryRays) of pixels the spp map gave 0 samples, traced for their
// guide planes only; no path sample starts from them.
struct RenderStats {
    uint64_t primaryRays = 0;
    uint64_t guideRays = 0;
    uint64_t shadowRays = 0;
    uint64_t shadowRaysReused = 0;
    uint64_t bounceRays = 0;
    uint64_t samples = 0;
    uint64_t droppedSamples = 0;
    // Rays actually traced.
    uint64_t Rays() const { return primaryRays + shadowRays - shadowRaysReused + bounceRays; }
};

// The surface sample a visibility-buffer entry names.
struct SurfaceSample {
    uint32_t instance = kNoObject;
    uint32_t primitive = kNoObject;
    vec2 barycentrics = vec2(0.0f);
};

class Renderer {
public:
    virtual ~Renderer() = default;

    // Moves the scene to `frame` at scene time `timeSeconds`: instance transforms, lights, BVH.
    // `frame` seeds the sampler and names the frame (the same frame twice is a no-op); a live
    // session's time need not be frame / frameRate (pause, playback speed).
    virtual void SetFrame(uint32_t frame, float timeSeconds) = 0;
    // The headless clock: time = frame / frameRate.
    void SetFrame(uint32_t frame) { SetFrame(frame, float(frame) / GetScene().frameRate); }
    virtual const SceneState& State() const = 0;
    // Turns A-SVGF gradient samples on or off (a live session switching denoisers); they start
    // on the frame after the next, once a previous frame's surface samples exist.
    virtual void SetGradientSamples(bool on) = 0;
    // Turns RenderSettings::fbetaPlane on or off from the next RenderEye (a live denoiser switch).
    virtual void SetFbetaPlane(bool on) = 0;
    virtual const Scene& GetScene() const = 0;

    // Renders one eye with n = spp(x, y) samples per pixel (n = 0: guide planes only) into `out` (allocated to the camera's
    // resolution) and the eye's visibility buffer (Visibility(eye)). `prevCamera` and the previous
    // frame's scene state give the motion vectors.
    // With gradient samples on, each gradient pixel instead holds the forward-projected previous
    // surface sample, shaded once with the previous seed and the previous n (A-SVGF §3; its
    // sampleCount says so). Set out.cameraCut before the call on a cut: gradient samples are then
    // skipped (as on frame 0).
    virtual void RenderEye(int eye, const EyeCamera& camera, const EyeCamera& prevCamera,
                           const Plane<uint16_t>& spp, FrameInputs& out) = 0;

    // The visibility buffer `eye`'s latest RenderEye filled (empty before the first): the surface
    // sample and seed each pixel was shaded with. Overwritten by the next RenderEye of that eye.
    virtual const VisibilityBuffer& Visibility(int eye) const = 0;

    // High-spp ground truth (remodulated colour) of the current frame for one eye. `seed` is the
    // reference's own sampling seed (ReferenceCache passes reference.seed mixed with the key's
    // frame), not the run seed: runs with different seeds are scored against the same reference.
    virtual void RenderReference(int eye, const EyeCamera& camera, int spp, uint32_t seed,
                                 Plane<vec3>& out) = 0;

    virtual RenderStats Stats() const = 0;
    virtual void ResetStats() = 0;
    // Starts over with run seed `seed` on the same scene and BVH: frame 0, no previous frame, no
    // eye history, counters at zero — the state CreateRenderer with that seed starts in, without
    // loading the scene or building its BVH again (an experiment's seeds share one renderer).
    virtual void Restart(uint32_t seed) = 0;
};

std::unique_ptr<Renderer> CreateRenderer(const Scene& scene, const RenderSettings& settings);

}  // namespace fovrt
