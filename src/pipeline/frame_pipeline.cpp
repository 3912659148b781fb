#include "pipeline/frame_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include <fmt/format.h>

#include "core/cpu_time.h"
#include "core/error.h"
#include "denoise/variants.h"
#include "gaze/tracker.h"
#include "pipeline/eye_sensitivity.h"
#include "pipeline/metric_display.h"

namespace fovrt {
namespace {

// The map's mean, rounded (at least 1), everywhere: the foveated map's rays spread evenly.
void MakeUniform(Plane<uint16_t>& sppMap) {
    if (sppMap.size() == 0) return;
    uint64_t total = 0;
    for (size_t p = 0; p < sppMap.size(); ++p) total += sppMap[p];
    const uint64_t mean = (total + sppMap.size() / 2) / sppMap.size();
    const uint16_t spp = uint16_t(std::clamp<uint64_t>(mean, 1, 65535));
    for (size_t p = 0; p < sppMap.size(); ++p) sppMap[p] = spp;
}

// A guide plane (noise-free, traced for every pixel, sampled or not) as luminance: the albedo is
// the content the masking term reads (under smooth light the image's local contrast is its
// texture's), the demodulation factor what the noise term divides out.
void GuideLuminance(const Plane<vec3>& guide, Plane<float>& out) {
    out.ResizeForOverwrite(guide.width(), guide.height());
    for (size_t i = 0; i < out.size(); ++i) out[i] = Luminance(guide[i]);
}


}  // namespace

std::string FrameOutputStem(uint32_t frame, int eye) {
    return fmt::format("f{:05d}_{}", frame, eye == 0 ? "left" : "right");
}

Fov ResolveFov(const RunConfig& config, const Scene& scene) {
    if (config.camera.fovDeg) {
        const auto& deg = *config.camera.fovDeg;
        return Fov{Radians(deg[0]), Radians(deg[1]), Radians(deg[2]), Radians(deg[3])};
    }
    float aspect = float(config.camera.width) / float(config.camera.height);
    return Fov::FromHorizontal(Radians(scene.horizontalFovDegrees), aspect);
}

FramePipeline::FramePipeline(const RunConfig& config)
    : config_(config), scene_(LoadScene(ResolveSceneName(config.scene.name))) {
    RequireSceneLight(scene_);
    // One clock for everything: the config's fps (when given) overrides the scene's frame rate,
    // so gaze, animation and motion vectors agree on what "frame i" means.
    if (config.run.fps > 0.0f) scene_.frameRate = config.run.fps;

    RenderSettings settings;
    settings.maxDepth = config.run.maxDepth;
    settings.seed = config.run.seed;
    settings.threads = config.run.threads;
    const RendererNeeds needs = RendererNeedsOf(config.denoise.denoisers, "denoise.denoisers");
    settings.gradientSamples = needs.gradientSamples;
    settings.fbetaPlane = needs.fbetaPlane;
    ParseDemodulation(config.render.demodulation, settings.demodulation);  // validated by the config
    renderer_ = CreateRenderer(scene_, settings);
    MakeGazeAndFoveation();
}

void FramePipeline::MakeGazeAndFoveation() {
    sppModel_ = CreateSppModel(config_.foveation, MetricContrastSensitivity(), MetricContrastMasking());
    tracked_.reset();
    gaze_ = CreateGazeSource(config_.gaze, ResolveFov(config_, scene_));
    tracked_ = std::make_unique<TrackedGaze>(*gaze_, config_.gaze.tracker);
}

void FramePipeline::Restart(uint32_t seed) {
    config_.run.seed = seed;
    renderer_->Restart(seed);
    MakeGazeAndFoveation();
    hasPrevious_ = false;
    previousFrame_ = 0;
}

int64_t FramePipeline::GazeFrames() const {
    const double end = gaze_->EndSeconds();
    if (!(end < 1e12)) return std::numeric_limits<int64_t>::max();
    // Frame i is at i / fps; the slack keeps a frame that lands on the last row (rounding).
    return int64_t(std::floor(end * double(scene_.frameRate) + 1e-6)) + 1;
}

void FramePipeline::CheckGazeCovers(uint32_t firstFrame, int frames) const {
    const int64_t needed = int64_t(firstFrame) + frames, available = GazeFrames();
    if (needed <= available) return;
    const GazeParams& gaze = config_.gaze;
    const bool recording = gaze.source == "recording";
    const std::string file = fmt::format("{} '{}'", recording ? "gaze.recording_path" : "gaze.trace_path",
                                         recording ? gaze.recordingPath : gaze.tracePath);
    if (gaze.traceEnd == "refuse")
        Fail("gaze.trace_end = \"refuse\": frames {}..{} (run.first_frame, run.frames at {} fps) need {} frames of "
             "gaze but {} from gaze.trace_start_ms = {} has {} ({:.6g} s); lower run.frames, or set gaze.trace_end = "
             "\"hold\" or \"loop\"",
             firstFrame, needed - 1, scene_.frameRate, needed, file, gaze.traceStartMs, available,
             gaze_->EndSeconds());
    std::fprintf(stderr,
                 "fovrt: warning: gaze.trace_end = \"hold\": frames %lld..%lld are past the end of %s and hold its "
                 "last row (frames.jsonl marks them gaze_held)\n",
                 static_cast<long long>(std::max<int64_t>(available, firstFrame)), static_cast<long long>(needed - 1),
                 file.c_str());
}

void FramePipeline::SetFoveation(const FoveationParams& params) {
    sppModel_ = CreateSppModel(params, MetricContrastSensitivity(), MetricContrastMasking());
    config_.foveation = params;
    // Kept only while the content and noise terms are on: after they were off, what is held is
    // from an older frame.
    for (Plane<float>& content : previousContent_) content = Plane<float>();
    for (VisibleNoiseEstimator& noise : visibleNoise_) noise.Reset();
}

StereoRig FramePipeline::RigAtTime(double timeSeconds) const {
    StereoRig rig;
    rig.head = scene_.HeadAt(float(timeSeconds));
    rig.ipd = config_.camera.ipd;
    rig.fov[0] = rig.fov[1] = ResolveFov(config_, scene_);
    rig.width = config_.camera.width;
    rig.height = config_.camera.height;
    return rig;
}

void FramePipeline::SetFrame(uint32_t frame) {
    renderer_->SetFrame(frame);
    hasPrevious_ = false;  // the next Render() after a jump is a cut
}

FrameRequest FramePipeline::RequestAt(uint32_t frame) const {
    FrameRequest request;
    request.frame = frame;
    request.timeSeconds = TimeOf(frame);
    const StereoRig rig = RigAt(frame);
    for (int eye = 0; eye < 2; ++eye) request.eyes[size_t(eye)] = rig.Eye(eye);
    request.gaze = tracked_->At(request.timeSeconds);
    if (!IsIdealTracker(config_.gaze.tracker)) request.trueGaze = gaze_->At(request.timeSeconds);
    return request;
}

void FramePipeline::Render(const FrameRequest& request, StereoFrame& out) {
    const uint32_t frame = request.frame;
    bool cut = !hasPrevious_ || frame != previousFrame_ + 1;
    renderer_->SetFrame(frame, float(request.timeSeconds));
    out.frame = frame;
    out.timeSeconds = request.timeSeconds;
    out.gaze = request.gaze;
    out.trueGaze = request.EyeGaze();

    for (int eye = 0; eye < 2; ++eye) {
        EyeFrame& eyeFrame = out.eyes[size_t(eye)];
        const EyeCamera& camera = request.eyes[size_t(eye)];
        EyeCamera prevCamera = cut ? camera : previousCameras_[size_t(eye)];
        eyeFrame.camera = camera;

        auto start = std::chrono::steady_clock::now();
        eyeFrame.gazeEye = GazeInEye(camera, out.gaze.direction);
        eyeFrame.gazePixel = GazePixel(camera, out.gaze.direction);
        eyeFrame.trueGazeEye = GazeInEye(camera, out.trueGaze.direction);
        eyeFrame.trueGazePixel = GazePixel(camera, out.trueGaze.direction);
        // After a cut the previous frames' content and noise do not belong to this view: flat.
        const Plane<float>& content = previousContent_[size_t(eye)];
        VisibleNoiseEstimator& noise = visibleNoise_[size_t(eye)];
        if (cut) noise.Reset();
        FrameFeedback feedback;
        if (!cut && content.width() == camera.width() && content.height() == camera.height()) feedback.content = &content;
        if (noise.Noise().Valid() && noise.Noise().Matches(camera.width(), camera.height()))
            feedback.noise = &noise.Noise();
        sppModel_->Generate(camera, eyeFrame.gazeEye, frame, eyeFrame.sppMap, feedback);
        eyeFrame.uniformForBlink = !out.gaze.valid && config_.gaze.blink == "uniform";
        if (eyeFrame.uniformForBlink) MakeUniform(eyeFrame.sppMap);
        eyeFrame.sppMs = MsSince(start);

        start = std::chrono::steady_clock::now();
        eyeFrame.inputs.cameraCut = cut;
        renderer_->RenderEye(eye, camera, prevCamera, eyeFrame.sppMap, eyeFrame.inputs);
        eyeFrame.inputs.cameraCut = cut;
        eyeFrame.inputs.frameIndex = frame;
        eyeFrame.inputs.gazePixel = eyeFrame.gazePixel;
        eyeFrame.inputs.timeSeconds = out.timeSeconds;
        eyeFrame.renderMs = MsSince(start);
        previousCameras_[size_t(eye)] = camera;
        if (config_.foveation.contentMasking) GuideLuminance(eyeFrame.inputs.albedo, previousContent_[size_t(eye)]);
        // As the metric sees the frame: the display's luminance at the PNGs' exposure. Timed with
        // the map it serves.
        if (config_.foveation.noiseVisibility) {
            start = std::chrono::steady_clock::now();
            const FrameInputs& in = eyeFrame.inputs;
            Plane<float>& modulation = noiseModulation_[size_t(eye)];
            GuideLuminance(in.Modulation(), modulation);
            noise.Add(VdpDisplayLuminance(in.NoisyImage(), config_.output.exposure,
                                          ExperimentVdpDisplay(config_, camera).photometry),
                      in.sampleCount, {&modulation, &in.objectId});
            eyeFrame.sppMs += MsSince(start);
        }
    }
    hasPrevious_ = true;
    previousFrame_ = frame;
}

}  // namespace fovrt
