#include "live/live_loop.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "core/error.h"
#include "denoise/denoiser_factory.h"
#include "denoise/variants.h"
#include "pipeline/metric_fovea.h"
#include "pipeline/reference_cache.h"

namespace fovrt {
namespace {

void AddTimings(const std::vector<PassTiming>& eye, std::vector<PassTiming>& sum) {
    for (const PassTiming& t : eye) {
        auto it = std::find_if(sum.begin(), sum.end(), [&](const PassTiming& s) { return s.pass == t.pass; });
        if (it == sum.end()) sum.push_back(t);
        else it->ms += t.ms;
    }
}

}  // namespace

namespace {
// The pipeline's own gaze source is never asked in a live session (the FrameSource gives the
// gaze); the mouse, which only a window has, is stood in for by a static one.
RunConfig PipelineConfig(RunConfig config) {
    if (config.gaze.source == "mouse") config.gaze.source = "static";
    return config;
}
}  // namespace

LiveLoop::LiveLoop(const RunConfig& config, VulkanContext* context, FrameSource& source)
    : config_(config), context_(context), source_(source), pipeline_(PipelineConfig(config)) {
    if (config.denoise.denoisers.empty()) Fail("denoise.denoisers: a live session needs one denoiser");
    controls_.denoiser = config.denoise.denoisers.front();
    controls_.foveation = config.foveation;
    runningFoveation_ = config.foveation;
    ApplyDenoiser(controls_.denoiser);
}

LiveLoop::~LiveLoop() { Stop(); }

void LiveLoop::Start(uint64_t maxFrames, bool pipelined) {
    maxFrames_ = maxFrames;
    pipelined_ = pipelined;
    tracing_ = true;
    traceThread_ = std::thread([this] { TraceThread(); });
    if (pipelined_) denoiseThread_ = std::thread([this] { DenoiseThread(); });
}

std::shared_ptr<const LiveFrame> LiveLoop::RenderOne() {
    if (traceThread_.joinable()) Fail("LiveLoop::RenderOne while the render thread runs");
    const LiveControls controls = Controls();
    auto frame = Trace(controls);
    Finish(*frame, controls);
    return Latest();
}

void LiveLoop::Stop() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    handoffFree_.notify_all();
    handoffFull_.notify_all();
    if (traceThread_.joinable()) traceThread_.join();
    if (denoiseThread_.joinable()) denoiseThread_.join();
}

bool LiveLoop::Finished() const { return finished_.load(); }

std::optional<std::string> LiveLoop::Error() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return error_;
}

std::shared_ptr<const LiveFrame> LiveLoop::Latest() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return latest_;
}

LiveControls LiveLoop::Controls() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return controls_;
}

void LiveLoop::SetDenoiser(const std::string& name) {
    FindDenoiserVariant(name, "denoiser");  // an unknown name fails here, not on the render thread
    std::lock_guard<std::mutex> lock(mutex_);
    controls_.denoiser = name;
}

void LiveLoop::SetView(const std::string& name) {
    std::lock_guard<std::mutex> lock(mutex_);
    controls_.view = name;
}

void LiveLoop::SetFoveation(const FoveationParams& params) {
    ValidateFoveationParams(params);
    std::lock_guard<std::mutex> lock(mutex_);
    controls_.foveation = params;
}

void LiveLoop::SetPaused(bool paused) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        controls_.paused = paused;
    }
    wake_.notify_all();
}

void LiveLoop::Step() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        ++pendingSteps_;
    }
    wake_.notify_all();
}

void LiveLoop::SetSpeed(float speed) {
    std::lock_guard<std::mutex> lock(mutex_);
    controls_.speed = std::max(0.0f, speed);
}

std::vector<std::string> LiveLoop::ViewNames() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return viewNames_;
}

std::vector<BufferPlan> LiveLoop::DenoiserMemory() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return memory_;
}

void LiveLoop::OnFrameStart(std::function<void(const SourcedFrame&)> callback) {
    onFrameStart_ = std::move(callback);
}

void LiveLoop::OnFrameDone(std::function<void(const LiveFrame&)> callback) {
    onFrameDone_ = std::move(callback);
}

void LiveLoop::ApplyDenoiser(const std::string& name) {
    DenoiserParams params = ParamsForDenoiser(name, config_.denoise.params, PrecisionTargetOf(context_));
    // The foveation changes at run time (ApplyFoveation), and with it whether the spp map holds
    // zeros: every denoiser is built to keep a pixel without a path sample.
    params.sampleCountsMayBeZero = true;
    for (auto& d : denoisers_) d = CreateDenoiser(name, config_.denoise.device, params, context_);
    if (!runningDenoiser_.empty())
        std::fprintf(stderr, "fovrt: denoiser %s -> %s (histories reset)\n",
                     runningDenoiser_.c_str(), name.c_str());
    runningDenoiser_ = name;
    std::vector<BufferPlan> memory;  // the eyes share the transient pool (vk/shared_buffers.h)
    const std::vector<BufferPlan> eye = PlanDenoiserMemory(name, config_.camera.width, config_.camera.height, params);
    for (const char* prefix : {"left.", "right."}) AddDenoiserOnDevice(memory, prefix, eye);
    std::lock_guard<std::mutex> lock(mutex_);
    viewNames_ = ViewNamesFor(*denoisers_[0]);
    memory_ = std::move(memory);
}

void LiveLoop::ApplyFoveation(const FoveationParams& params) {
    pipeline_.SetFoveation(params);
    runningFoveation_ = params;
}

void LiveLoop::TraceThread() {
    try {
        while (true) {
            LiveControls controls;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [&] { return stop_ || !controls_.paused || pendingSteps_ > 0; });
                if (stop_) break;
                if (controls_.paused) --pendingSteps_;
                controls = controls_;
            }
            auto frame = Trace(controls);
            if (!pipelined_) {
                Finish(*frame, controls);
            } else {
                std::unique_lock<std::mutex> lock(mutex_);
                handoffFree_.wait(lock, [&] { return stop_ || !handoff_; });
                if (stop_) break;
                handoff_ = Handoff{std::move(frame), controls};
                handoffFull_.notify_all();
            }
            if (maxFrames_ && ++traced_ >= maxFrames_) break;
        }
    } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(mutex_);
        error_ = e.what();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    tracing_ = false;
    if (!pipelined_) finished_ = true;
    handoffFull_.notify_all();
}

void LiveLoop::DenoiseThread() {
    try {
        while (true) {
            Handoff next;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                handoffFull_.wait(lock, [&] { return stop_ || handoff_ || !tracing_; });
                if (stop_ || !handoff_) break;
                next = std::move(*handoff_);
                handoff_.reset();
                handoffFree_.notify_all();
            }
            Finish(*next.frame, next.controls);
        }
    } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(mutex_);
        error_ = e.what();
        stop_ = true;
        wake_.notify_all();
        handoffFree_.notify_all();
    }
    finished_ = true;
}

std::shared_ptr<LiveFrame> LiveLoop::Trace(const LiveControls& controls) {
    if (controls.denoiser != tracedDenoiser_) {
        // Gradient samples and F_β as the new denoiser needs them; its histories start at this frame.
        pipeline_.SetRendererNeeds(RendererNeedsOf({controls.denoiser}, "denoiser"));
        pipeline_.Cut();
        tracedDenoiser_ = controls.denoiser;
    }
    if (!(controls.foveation == runningFoveation_)) ApplyFoveation(controls.foveation);

    auto frame = std::make_shared<LiveFrame>();
    frame->startedAt = LiveClock::now();
    frame->source = source_.Next(frameIndex_, sceneTime_);
    if (onFrameStart_) onFrameStart_(frame->source);

    const RenderStats before = pipeline_.GetRenderer().Stats();
    pipeline_.Render(frame->source.request, frame->stereo);
    const RenderStats after = pipeline_.GetRenderer().Stats();
    frame->timings.rays = after.Rays() - before.Rays();
    frame->timings.guideRays = after.guideRays - before.guideRays;
    for (int eye = 0; eye < 2; ++eye) {
        const EyeFrame& e = frame->stereo.eyes[size_t(eye)];
        frame->timings.sppMs += e.sppMs;
        frame->timings.traceMs += e.renderMs;
        frame->gazePixel[size_t(eye)] = e.gazePixel;
        frame->trueGazePixel[size_t(eye)] = frame->source.request.trueGaze
                                                ? e.trueGazePixel
                                                : vec2(std::numeric_limits<float>::quiet_NaN());
        frame->foveaRadiusPixels[size_t(eye)] = MetricFovea(runningFoveation_, e.camera.width()).RadiusPixels(e.camera);
    }
    ++frameIndex_;
    sceneTime_ += double(controls.speed) / double(pipeline_.FramesPerSecond());
    return frame;
}

void LiveLoop::Finish(LiveFrame& frameRef, const LiveControls& controls) {
    LiveFrame* frame = &frameRef;
    const bool switched = controls.denoiser != runningDenoiser_;
    if (switched) ApplyDenoiser(controls.denoiser);
    // A debug view reads the denoiser's planes, some of them in the transient pool that the other
    // eye's frame reuses (vk/shared_buffers.h): it is built before that frame runs.
    std::array<bool, 2> built{};
    double debugViewMs = 0.0;
    for (int eye = 0; eye < 2; ++eye) {
        EyeFrame& e = frame->stereo.eyes[size_t(eye)];
        Denoiser& denoiser = *denoisers_[size_t(eye)];
        const auto denoiseStart = LiveClock::now();
        denoiser.Denoise(e.inputs, frame->denoised[size_t(eye)]);
        frame->timings.denoiseMs += MsBetween(denoiseStart, LiveClock::now());
        AddTimings(denoiser.LastTimings(), frame->timings.passes);
        const std::vector<std::string> views = denoiser.DebugViews();
        if (std::find(views.begin(), views.end(), controls.view) == views.end()) continue;
        const auto viewStart = LiveClock::now();
        ViewSources sources{&e.inputs, &e.sppMap, &frame->denoised[size_t(eye)], nullptr, &denoiser, nullptr,
                            e.trueGazePixel};
        built[size_t(eye)] = BuildView(controls.view, sources, frame->shown[size_t(eye)]);
        debugViewMs += MsBetween(viewStart, LiveClock::now());
    }

    const auto viewStart = LiveClock::now();
    std::array<std::optional<Plane<vec3>>, 2> references;
    const bool vdpView = controls.view == "vdp";
    if (controls.view == "error" || vdpView) {
        if (!referenceCache_) {
            referenceCache_ = std::make_unique<ReferenceCache>(config_.reference.cacheDir);
            fingerprint_ = SceneFingerprint(pipeline_.GetScene());
        }
        for (int eye = 0; eye < 2; ++eye) {
            const EyeFrame& e = frame->stereo.eyes[size_t(eye)];
            references[size_t(eye)] = referenceCache_->Find(MakeReferenceKey(
                pipeline_.GetScene(), fingerprint_, frame->stereo.frame, frame->stereo.timeSeconds, eye,
                e.camera, config_.reference.spp, config_.run.maxDepth, config_.reference.seed));
        }
    }
    frame->view = controls.view;
    for (int eye = 0; eye < 2; ++eye) {
        const EyeFrame& e = frame->stereo.eyes[size_t(eye)];
        std::unique_ptr<VdpViewStream>& vdp = vdpViews_[size_t(eye)];
        // The metric's temporal channels see one sequence: a new view, denoiser, cut or a gap
        // in the references starts it again.
        if (!vdpView || switched || e.inputs.cameraCut || !references[size_t(eye)]) vdp.reset();
        if (built[size_t(eye)]) continue;
        if (vdpView && references[size_t(eye)] && !vdp)
            vdp = std::make_unique<VdpViewStream>(config_, e.camera, pipeline_.FramesPerSecond());
        ViewSources sources{&e.inputs, &e.sppMap, &frame->denoised[size_t(eye)],
                            references[size_t(eye)] ? &*references[size_t(eye)] : nullptr,
                            denoisers_[size_t(eye)].get(), vdp.get(), e.trueGazePixel};
        if (!BuildView(controls.view, sources, frame->shown[size_t(eye)])) {
            BuildView("denoised", sources, frame->shown[size_t(eye)]);
            frame->shown[size_t(eye)].legend =
                controls.view == "error" || vdpView
                    ? "no cached reference for this view: showing denoised (run `fovrt reference`)"
                    : "view '" + controls.view + "' not available: showing denoised";
        }
    }
    frame->timings.viewMs = debugViewMs + MsBetween(viewStart, LiveClock::now());
    frame->denoiser = runningDenoiser_;
    frame->finishedAt = LiveClock::now();
    frame->timings.frameMs = MsBetween(frame->startedAt, frame->finishedAt);
    frame->number = rendered_ + 1;
    if (onFrameDone_) onFrameDone_(*frame);
    auto published = std::make_shared<const LiveFrame>(std::move(frameRef));
    std::lock_guard<std::mutex> lock(mutex_);
    latest_ = std::move(published);
    // Counted once published: whoever sees FramesRendered() == n finds frame n in Latest().
    ++rendered_;
}

}  // namespace fovrt
