// FramePipeline: one stereo frame from a RunConfig — gaze source -> per-eye spp map -> path tracer
// -> FrameInputs per eye. Shared by `fovrt run`, `fovrt reference` and `fovrt experiment`, so every
// workflow renders exactly the same noisy inputs for the same config and seed.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "config/config.h"
#include "core/frame_inputs.h"
#include "denoise/variants.h"
#include "foveation/spp_model.h"
#include "gaze/gaze_source.h"
#include "pipeline/frame_request.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace fovrt {

struct EyeFrame {
    EyeCamera camera;
    FrameInputs inputs;
    Plane<uint16_t> sppMap;
    vec3 gazeEye = vec3(0, 0, -1);  // gaze direction in this eye's space: the spp map's centre
    vec2 gazePixel = vec2(0.0f);    // where the gaze lands on this eye's image
    vec3 trueGazeEye = vec3(0, 0, -1);  // where the eye really looked (the metrics' centre)
    vec2 trueGazePixel = vec2(0.0f);
    double sppMs = 0.0;             // building the spp map (and the noise estimate it reads next frame)
    double renderMs = 0.0;          // path tracing this eye
    bool uniformForBlink = false;   // gaze.blink = "uniform" replaced the map during a blink
};

struct StereoFrame {
    uint32_t frame = 0;
    double timeSeconds = 0.0;
    GazeSample gaze;  // the tracked gaze; valid false: a blink (gaze.blink says what the spp maps did)
    GazeSample trueGaze;  // where the eye really was (= gaze with an ideal tracker)
    std::array<EyeFrame, 2> eyes;
};

class FramePipeline {
public:
    explicit FramePipeline(const RunConfig& config);

    const Scene& GetScene() const { return scene_; }
    Renderer& GetRenderer() { return *renderer_; }
    const SppModel& GetSppModel() const { return *sppModel_; }
    const GazeSource& GetGazeSource() const { return *gaze_; }  // the true gaze
    const RunConfig& Config() const { return config_; }
    float FramesPerSecond() const { return scene_.frameRate; }
    double TimeOf(uint32_t frame) const { return double(frame) / double(scene_.frameRate); }

    // Frames 0 .. GazeFrames() - 1 have gaze of their own; later ones are past the end of a trace
    // or recording (gaze.trace_end = "hold" repeats its last row there). Unbounded: INT64_MAX.
    int64_t GazeFrames() const;
    bool GazeHeld(uint32_t frame) const { return int64_t(frame) >= GazeFrames(); }
    // A headless run of `frames` frames from `firstFrame` (run, experiment, dataset), before it
    // renders: refused in one line when it outlasts its trace or recording (gaze.trace_end =
    // "refuse"), a warning with "hold".
    void CheckGazeCovers(uint32_t firstFrame, int frames) const;

    // The stereo rig (head pose from the scene's camera path, IPD and FOV from the config).
    StereoRig RigAt(uint32_t frame) const { return RigAtTime(TimeOf(frame)); }
    StereoRig RigAtTime(double timeSeconds) const;

    // The headless request for `frame`: time frame / fps, eyes from RigAt, the tracked gaze and
    // (with a non-ideal tracker) the true gaze of the gaze source.
    FrameRequest RequestAt(uint32_t frame) const;

    // Renders both eyes of `request` into `out`. Frames are rendered in the order asked; the
    // previous call's cameras give the motion vectors, and a jump that is not the next frame is
    // treated as a camera cut (cameraCut = true, no history may be reused).
    void Render(const FrameRequest& request, StereoFrame& out);
    void Render(uint32_t frame, StereoFrame& out) { Render(RequestAt(frame), out); }
    // Live changes: a new spp model (foveation panel), what the renderer traces for the denoiser shown.
    void SetFoveation(const FoveationParams& params);
    void SetRendererNeeds(const RendererNeeds& needs) {
        renderer_->SetGradientSamples(needs.gradientSamples);
        renderer_->SetFbetaPlane(needs.fbetaPlane);
    }
    // The next Render() is a camera cut (a teleport, a denoiser switch, a resumed recording).
    void Cut() { hasPrevious_ = false; }

    // Starts over with run seed `seed`, as a FramePipeline built from the config with that
    // run.seed would start, but on the same scene and BVH (loaded and built once per scene): the
    // renderer restarts (render/renderer.h), the gaze sources and the spp model are made anew.
    void Restart(uint32_t seed);

    // Moves the scene to `frame` without rendering noisy inputs (for reference-only work).
    void SetFrame(uint32_t frame);

private:
    void MakeGazeAndFoveation();

    RunConfig config_;
    Scene scene_;
    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<SppModel> sppModel_;
    std::unique_ptr<GazeSource> gaze_;     // the true gaze
    std::unique_ptr<GazeSource> tracked_;  // what the tracker reports of it (gaze/tracker.h)
    bool hasPrevious_ = false;
    uint32_t previousFrame_ = 0;
    std::array<EyeCamera, 2> previousCameras_;
    // The previous frame's primary-hit albedo luminance per eye: the content the perceptual model's
    // content term reads (foveation.content_masking); empty when off.
    std::array<Plane<float>, 2> previousContent_;
    // The noise each eye's frames showed, as the display shows them: what the perceptual model's
    // noise term reads (foveation.noise_visibility); empty when off.
    std::array<VisibleNoiseEstimator, 2> visibleNoise_;
    // The demodulation factor's luminance per eye, which the noise term divides out: kept so that
    // a frame overwrites it instead of allocating it.
    std::array<Plane<float>, 2> noiseModulation_;
};

// The file stem of a frame's per-eye outputs: "f00012_left" (run, preview, replays).
std::string FrameOutputStem(uint32_t frame, int eye);

// The per-eye FOV the config asks for, or the symmetric default from the scene.
Fov ResolveFov(const RunConfig& config, const Scene& scene);

}  // namespace fovrt
