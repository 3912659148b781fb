// LiveLoop: the frame loop every live session runs (SPEC §11), on a render thread of its own:
//   FrameSource (gaze + head pose) -> per-eye spp maps -> path tracer -> denoiser (Vulkan) ->
//   the chosen view -> publish.
// The window (or the OpenXR session) never waits on it: it shows the newest published LiveFrame
// and keeps presenting while the next one renders. Controls (denoiser, view, foveation, pause,
// step, speed) may change at any time from any thread; they apply at the next frame start.
// Nothing accumulates per frame: each frame is published once and freed when no longer shown.
#pragma once

#include <array>
#include <atomic>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "config/config.h"
#include "denoise/denoiser.h"
#include "live/frame_source.h"
#include "live/views.h"
#include "pipeline/frame_pipeline.h"

namespace fovrt {

class ReferenceCache;
class VulkanContext;

struct LiveTimings {
    double sppMs = 0.0;      // both eyes
    double traceMs = 0.0;    // both eyes
    double denoiseMs = 0.0;  // both eyes, wall clock
    double viewMs = 0.0;
    double frameMs = 0.0;    // request to publish
    std::vector<PassTiming> passes;  // per denoiser pass, summed over the eyes
    uint64_t rays = 0;
    uint64_t guideRays = 0;  // of `rays`: primary rays of pixels without a path sample (guide planes only)
    double RaysPerSecond() const { return traceMs > 0.0 ? double(rays) / (traceMs * 1e-3) : 0.0; }
};

// One finished stereo frame, immutable once published.
struct LiveFrame {
    uint64_t number = 0;  // 1 for the first frame the loop rendered
    SourcedFrame source;
    LiveClock::time_point startedAt;   // the trace stage took the request
    LiveClock::time_point finishedAt;
    std::string denoiser;
    std::string view;
    std::array<ViewImage, 2> shown;
    std::array<vec2, 2> gazePixel{};      // the gaze the spp map follows (a tracker's)
    std::array<vec2, 2> trueGazePixel{};  // where the eye is; NaN without a tracker model (= gazePixel)
    std::array<float, 2> foveaRadiusPixels{};
    LiveTimings timings;
    // What F12 saves: the frame's inputs and spp maps, and each eye's denoised output.
    StereoFrame stereo;
    std::array<Plane<vec3>, 2> denoised;
};

struct LiveControls {
    std::string denoiser;   // a variant name (denoise/variants.h)
    std::string view = "denoised";
    FoveationParams foveation;
    bool paused = false;
    float speed = 1.0f;     // scene seconds per frame = speed / fps
};

class LiveLoop {
public:
    // `context`: the Vulkan device the denoisers run on (shared with the window); null runs the
    // C++ reference. The denoiser shown first is config.denoise.denoisers[0].
    LiveLoop(const RunConfig& config, VulkanContext* context, FrameSource& source);
    ~LiveLoop();  // stops the render thread

    // Starts rendering; stops by itself after `maxFrames` frames (0 = until Stop()).
    // pipelined: frame N+1 is traced while frame N is denoised (two threads, more frames per
    // second on a CPU where neither stage fills every core); otherwise each frame is traced and
    // denoised in turn (the gaze is sampled closest to the photons: lower latency).
    void Start(uint64_t maxFrames = 0, bool pipelined = false);
    // Renders one frame on the calling thread and returns it (published as Latest() too): for a
    // caller that paces frames itself, as an OpenXR session does between xrWaitFrame and
    // xrEndFrame. Not while Start()'s threads run. Throws what the render stages throw.
    std::shared_ptr<const LiveFrame> RenderOne();
    void Stop();
    bool Finished() const;  // stopped after maxFrames, or failed
    // The render thread's error, if it failed (the window shows it and exits non-zero).
    std::optional<std::string> Error() const;

    std::shared_ptr<const LiveFrame> Latest() const;
    uint64_t FramesRendered() const { return rendered_.load(); }

    LiveControls Controls() const;
    void SetDenoiser(const std::string& name);  // resets both eyes' histories (logged)
    void SetView(const std::string& name);
    void SetFoveation(const FoveationParams& params);
    void SetPaused(bool paused);
    void Step();                                // renders one frame while paused
    void SetSpeed(float speed);
    std::vector<std::string> ViewNames() const;  // of the denoiser now running
    // Every buffer of the running denoiser, both eyes (the panel's memory table).
    std::vector<BufferPlan> DenoiserMemory() const;
    const FramePipeline& Pipeline() const { return pipeline_; }
    const RunConfig& Config() const { return config_; }

    // Called on the render thread with each frame's request before it renders (recordings), and
    // with the finished frame before it is published (writing inputs). Set before Start().
    void OnFrameStart(std::function<void(const SourcedFrame&)> callback);
    void OnFrameDone(std::function<void(const LiveFrame&)> callback);

private:
    void TraceThread();
    void DenoiseThread();
    std::shared_ptr<LiveFrame> Trace(const LiveControls& controls);    // source -> spp -> tracer
    void Finish(LiveFrame& frame, const LiveControls& controls);       // denoise -> view -> publish
    void ApplyDenoiser(const std::string& name);
    void ApplyFoveation(const FoveationParams& params);

    RunConfig config_;
    VulkanContext* context_;
    FrameSource& source_;
    FramePipeline pipeline_;
    std::array<std::unique_ptr<Denoiser>, 2> denoisers_;
    std::string runningDenoiser_;  // the denoise stage's
    std::string tracedDenoiser_;   // the trace stage's (gradient samples, cut on a switch)
    FoveationParams runningFoveation_;
    std::function<void(const SourcedFrame&)> onFrameStart_;
    std::function<void(const LiveFrame&)> onFrameDone_;

    mutable std::mutex mutex_;
    std::condition_variable wake_;
    struct Handoff {
        std::shared_ptr<LiveFrame> frame;
        LiveControls controls;  // as the trace stage saw them: both stages switch on one frame
    };
    std::optional<Handoff> handoff_;  // one traced frame waiting for the denoise stage
    std::condition_variable handoffFree_, handoffFull_;
    bool pipelined_ = true;
    bool tracing_ = false;
    uint64_t traced_ = 0;
    LiveControls controls_;
    int pendingSteps_ = 0;
    bool stop_ = false;
    uint64_t maxFrames_ = 0;
    std::shared_ptr<const LiveFrame> latest_;
    std::optional<std::string> error_;
    std::atomic<uint64_t> rendered_{0};
    std::atomic<bool> finished_{false};
    std::vector<std::string> viewNames_;
    std::vector<BufferPlan> memory_;

    std::unique_ptr<ReferenceCache> referenceCache_;  // opened when the error view is first shown
    uint64_t fingerprint_ = 0;
    // The "vdp" view's metric per eye (denoise stage): made when the view is shown, dropped when
    // another view, another denoiser, a cut or a frame without reference ends the sequence.
    std::array<std::unique_ptr<VdpViewStream>, 2> vdpViews_;

    uint32_t frameIndex_ = 0;
    double sceneTime_ = 0.0;
    std::thread traceThread_, denoiseThread_;
};


}  // namespace fovrt
