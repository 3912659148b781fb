#include "xr/xr_app.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "config/config_io.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "io/png.h"
#include "live/live_loop.h"
#include "live/live_session.h"
#include "live/live_stats.h"
#include "live/tracked_frame_source.h"
#include "pipeline/build_info.h"
#include "pipeline/denoiser_set.h"
#include "vk/context.h"
#include "xr/xr_connection.h"
#include "xr/xr_eye_gaze.h"
#include "xr/xr_frame_source.h"
#include "xr/xr_mirror.h"
#include "xr/xr_session.h"
#include "xr/xr_swapchain.h"

namespace fovrt {
namespace {

namespace fs = std::filesystem;

std::atomic<bool> g_interrupted{false};
extern "C" void OnInterrupt(int) { g_interrupted = true; }

// Ctrl-C asks the runtime to end the session (xrRequestExitSession) instead of killing it.
class InterruptGuard {
public:
    InterruptGuard() {
        g_interrupted = false;
        previous_ = std::signal(SIGINT, OnInterrupt);
        previousTerm_ = std::signal(SIGTERM, OnInterrupt);
    }
    ~InterruptGuard() {
        std::signal(SIGINT, previous_);
        std::signal(SIGTERM, previousTerm_);
    }

private:
    void (*previous_)(int);
    void (*previousTerm_)(int);
};

nlohmann::json PoseJson(const Pose& pose) {
    return {{"position", {pose.position.x, pose.position.y, pose.position.z}},
            {"orientation_xyzw", {pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w}}};
}

// The eyes are rendered at the headset's recommended size (one swapchain per eye at that size).
RunConfig HeadsetConfig(RunConfig config, const XrConnection& connection) {
    const auto& views = connection.views();
    config.camera.width = int(views[0].recommendedImageRectWidth);
    config.camera.height = int(views[0].recommendedImageRectHeight);
    if (views[1].recommendedImageRectWidth != views[0].recommendedImageRectWidth ||
        views[1].recommendedImageRectHeight != views[0].recommendedImageRectHeight)
        std::fprintf(stderr, "fovrt xr: warning: the eyes' recommended sizes differ (%ux%u, %ux%u): both use the left's\n",
                     views[0].recommendedImageRectWidth, views[0].recommendedImageRectHeight,
                     views[1].recommendedImageRectWidth, views[1].recommendedImageRectHeight);
    return config;
}

class XrApp {
public:
    XrApp(const RunConfig& config, const XrOptions& options) : options_(options) {
        connection_ = std::make_unique<XrConnection>();
        config_ = HeadsetConfig(config, *connection_);
        VulkanContextOptions vkOptions;
        const std::string device = LiveDisplayDevice(config_);
        if (options.mirror) {
            try {
                window_.emplace(options.window);
            } catch (const Error& e) {
                Fail("--mirror: {}; or leave out --mirror", e.what());
            }
            vkOptions = window_->ContextOptions(device);
        } else {
            vkOptions.device = device;
        }
        connection_->InstallVulkanCreation(vkOptions);
        context_.emplace(VulkanContext::Create(vkOptions));
        if (window_) mirror_.emplace(*window_, *context_, options);

        session_.emplace(*connection_, *context_);
        if (connection_->eyeGazeSupported()) gaze_.emplace(*connection_, session_->handle());
        const VkFormat format = XrEyeSwapchain::ChooseFormat(session_->handle());
        for (auto& swapchain : swapchains_)
            swapchain.emplace(session_->handle(), *context_, format, uint32_t(config_.camera.width),
                              uint32_t(config_.camera.height));
        writer_.emplace(*context_, options_.writeFrames);

        source_.emplace(config_, options.followPath);
        tracked_.emplace(*source_, config_.gaze.tracker);  // the eye-tracker model over the headset's gaze
        if (mirror_) mirror_->SetTracker(&*tracked_);
        loop_.emplace(config_, &*context_, *tracked_);
        source_->Bind(loop_->Pipeline());
        wiring_.emplace(*loop_, options.session,
                        nlohmann::json{{"source", "openxr"},
                                       {"runtime", connection_->runtimeName()},
                                       {"system", connection_->systemName()}});
        stats_.emplace(options.session.stats);

        outDir_ = fs::path(config_.output.dir) / "xr";
        fs::create_directories(outDir_);
        fs::remove(outDir_ / "manifest.json");  // present only once this session is over
        frameLog_ = std::fopen((outDir_ / "frames.jsonl").c_str(), "w");
        if (!frameLog_) Fail("output.dir: cannot write {}", (outDir_ / "frames.jsonl").string());
        if (options.writeFrames) fs::create_directories(outDir_ / "frames");
    }

    ~XrApp() {
        if (frameLog_) std::fclose(frameLog_);
    }

    void Run() {
        const auto& sc = *swapchains_[0];
        std::fprintf(stderr,
                     "fovrt xr: runtime '%s', system '%s', %ux%u per eye (VkFormat %d), denoiser %s on %s, eye gaze %s\n",
                     connection_->runtimeName().c_str(), connection_->systemName().c_str(), sc.width(), sc.height(),
                     int(sc.format()), loop_->Controls().denoiser.c_str(), context_->deviceName().c_str(),
                     connection_->eyeGazeSupported() ? "supported" : "not supported");
        if (!connection_->eyeGazeSupported())
            std::fprintf(stderr,
                         "fovrt xr: warning: the system has no eye gaze interaction: gaze from gaze.source = %s\n",
                         source_->FallbackName().c_str());
        InterruptGuard interrupt;
        start_ = LiveClock::now();
        while (true) {
            session_->PollEvents();
            if (session_->Ended() != XrSessionEnd::None) break;
            if (g_interrupted && !session_->ExitRequested()) {
                std::fprintf(stderr, "fovrt xr: interrupted: asking the runtime to end the session\n");
                session_->RequestExit();
            }
            if (mirror_ && mirror_->Closed() && !session_->ExitRequested()) session_->RequestExit();
            if (session_->Ended() != XrSessionEnd::None) break;
            if (!session_->Running()) {
                if (mirror_) mirror_->Present(*loop_, *stats_, last_, SessionLines());
                std::this_thread::sleep_for(std::chrono::milliseconds(5));
                continue;
            }
            RunFrame();
        }
        Finish();
    }

private:
    void RunFrame() {
        const auto waitStart = LiveClock::now();
        const XrHeadsetSession::FrameTiming timing = session_->BeginFrame();
        waitMs_ = MsBetween(waitStart, LiveClock::now());
        if (session_->Ended() != XrSessionEnd::None) return;
        const bool wanted = !AllFramesSubmitted() && !session_->ExitRequested();
        std::vector<XrCompositionLayerProjectionView> layer;
        std::shared_ptr<const LiveFrame> fresh;  // a frame submitted for the first time
        if (timing.shouldRender && wanted) {
            const auto views = session_->LocateViews(timing.displayTime);
            const auto head = session_->LocateHead(timing.displayTime);
            if (views && head) {
                if (!options_.async) {
                    if (!(loop_->Controls().paused && last_)) {
                        SetNextFrame(timing, *views, *head);
                        fresh = loop_->RenderOne();
                    }
                } else {
                    // The render thread takes the newest views and gaze whenever it starts a frame;
                    // this thread submits the newest finished frame at every display slot.
                    SetNextFrame(timing, *views, *head);
                    if (!loopStarted_) {
                        loop_->Start(options_.frames, false);
                        loopStarted_ = true;
                    }
                    if (auto error = loop_->Error()) Fail("render thread: {}", *error);
                    auto latest = loop_->Latest();
                    if (latest && (!last_ || latest->number != last_->number)) fresh = latest;
                }
                if (fresh) {
                    last_ = fresh;
                    lastLayer_ = WriteEyes(*fresh);
                    ++submitted_;
                }
                // Nothing new: the last released images again, with the poses they were traced
                // from (the compositor reprojects them to the current head pose).
                layer = lastLayer_;
            }
        }
        const auto endStart = LiveClock::now();
        session_->EndFrame(timing.displayTime, layer);
        const auto submitted = LiveClock::now();
        if (fresh && session_->Ended() == XrSessionEnd::None) Log(*fresh, timing, endStart, submitted);
        if (AllFramesSubmitted() && !session_->ExitRequested()) {
            std::fprintf(stderr, "fovrt xr: %llu frames submitted: ending the session\n",
                         (unsigned long long)submitted_);
            session_->RequestExit();
        }
        if (mirror_) mirror_->Present(*loop_, *stats_, last_, SessionLines());
    }

    bool AllFramesSubmitted() const { return options_.frames && last_ && last_->number >= options_.frames; }

    // Eye gaze at the display time (or the fallback) and the located views, for the next frame.
    void SetNextFrame(const XrHeadsetSession::FrameTiming& timing, const std::array<XrEyeView, 2>& views,
                      const Pose& head) {
        const auto gazeTakenAt = LiveClock::now();
        std::optional<vec3> tracked;
        if (gaze_)
            if (auto sample = gaze_->Locate(session_->viewSpace(), timing.displayTime)) tracked = sample->directionHead;
        // Inputs flow only while FOCUSED: before that the fallback is expected, not news.
        if (gaze_ && !tracked && !warnedInactive_ && session_->State() == XR_SESSION_STATE_FOCUSED) {
            std::fprintf(stderr,
                         "fovrt xr: warning: the eye gaze action is not active (no eye tracker delivering): gaze "
                         "from gaze.source = %s until it is\n",
                         source_->FallbackName().c_str());
            warnedInactive_ = true;
        }
        if (!firstDisplayTime_) firstDisplayTime_ = timing.displayTime;
        const double sceneTime = double(timing.displayTime - *firstDisplayTime_) * 1e-9 * double(options_.speed);
        source_->Set(views, head, sceneTime, tracked, gazeTakenAt);
    }

    // Both eyes into their swapchains; the layer's views carry the poses the frame was traced from.
    std::vector<XrCompositionLayerProjectionView> WriteEyes(const LiveFrame& frame) {
        const auto issued = source_->IssuedFrame(frame.source.request.frame);
        if (!issued) Fail("xr: frame {} was not issued by the headset source", frame.source.request.frame);
        std::array<VkImage, 2> images{};
        for (int eye = 0; eye < 2; ++eye) images[size_t(eye)] = swapchains_[size_t(eye)]->Acquire();
        DisplaySettings settings;
        settings.mode = frame.shown[0].hdr ? DisplayMode::Hdr : DisplayMode::Display;
        settings.exposure = config_.output.exposure;
        writer_->Write({&frame.shown[0].rgb, &frame.shown[1].rgb}, settings, {&*swapchains_[0], &*swapchains_[1]},
                       images);
        std::vector<XrCompositionLayerProjectionView> views(
            2, XrInit<XrCompositionLayerProjectionView>(XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW));
        for (int eye = 0; eye < 2; ++eye) {
            swapchains_[size_t(eye)]->Release();
            auto& v = views[size_t(eye)];
            v.pose = PoseToXr(issued->views[size_t(eye)].pose);
            v.fov = FovToXr(issued->views[size_t(eye)].fov);
            v.subImage.swapchain = swapchains_[size_t(eye)]->handle();
            v.subImage.imageRect.offset = {0, 0};
            v.subImage.imageRect.extent = {int32_t(swapchains_[size_t(eye)]->width()),
                                           int32_t(swapchains_[size_t(eye)]->height())};
            v.subImage.imageArrayIndex = 0;
        }
        return views;
    }

    void Log(const LiveFrame& frame, const XrHeadsetSession::FrameTiming& timing, LiveClock::time_point endStart,
             LiveClock::time_point submitted) {
        const double latencyMs = MsBetween(frame.source.gazeTakenAt, submitted);
        const auto issued = source_->IssuedFrame(frame.source.request.frame);
        const double submitMs = writer_->lastMs() + MsBetween(endStart, submitted);
        stats_->Add({frame.number, latencyMs, submitMs, frame.timings});
        const SourcedFrame& s = frame.source;
        nlohmann::json eyes = nlohmann::json::array();
        for (int eye = 0; eye < 2; ++eye) {
            const XrEyeView& v = issued->views[size_t(eye)];
            eyes.push_back({{"local", PoseJson(v.pose)},
                            {"fov", {v.fov.angleLeft, v.fov.angleRight, v.fov.angleUp, v.fov.angleDown}},
                            {"gaze_pixel", {frame.gazePixel[size_t(eye)].x, frame.gazePixel[size_t(eye)].y}}});
        }
        nlohmann::json line = {
            {"frame", s.request.frame},
            {"xr_frame", session_->FramesEnded()},  // the xrEndFrame (1-based) that submitted it
            {"display_time_ns", timing.displayTime},
            {"scene_time_s", s.request.timeSeconds},
            {"gaze_source", issued->gazeSource},
            {"gaze_direction", {s.request.gaze.direction.x, s.request.gaze.direction.y, s.request.gaze.direction.z}},
            {"eyes", eyes},
            {"gaze_to_submit_ms", latencyMs},
            {"ms",
             {{"wait_begin_frame", waitMs_},
              {"spp", frame.timings.sppMs},
              {"trace", frame.timings.traceMs},
              {"denoise", frame.timings.denoiseMs},
              {"write_eyes", writer_->lastMs()},
              {"end_frame", MsBetween(endStart, submitted)}}}};
        if (const auto& eye = s.request.trueGaze)  // a tracker model: gaze_direction is the tracked gaze
            line["true_gaze_direction"] = {eye->direction.x, eye->direction.y, eye->direction.z};
        std::fprintf(frameLog_, "%s\n", line.dump().c_str());
        std::fflush(frameLog_);
        // The bytes the device composed for each eye's swapchain image (the last Write was this
        // frame's), not the C++ display transform of the same frame: the two may differ by 1 in
        // a rare byte (shaders/common/display_transform.glsl).
        if (options_.writeFrames)
            for (int eye = 0; eye < 2; ++eye)
                WriteRgb8Png(outDir_ / "frames" / (FrameOutputStem(s.request.frame, eye) + ".png"),
                             swapchains_[size_t(eye)]->width(), swapchains_[size_t(eye)]->height(),
                             writer_->SentRgb8(eye));
    }

    std::vector<std::string> SessionLines() const {
        return {fmt::format("runtime: {}", connection_->runtimeName()),
                fmt::format("system: {}, {}x{} per eye", connection_->systemName(), config_.camera.width,
                            config_.camera.height),
                fmt::format("session: {}", XrSessionStateName(session_->State())),
                fmt::format("gaze: {}", source_->LastGazeSource().empty() ? "-" : source_->LastGazeSource()),
                fmt::format("frames: {} ended, {} with a layer, {} rendered, {} submitted", session_->FramesEnded(),
                            session_->FramesWithLayers(), loop_->FramesRendered(), submitted_)};
    }

    void Finish() {
        loop_->Stop();  // --async: the render thread (the recorder's writer) first
        wiring_->Close();
        const XrSessionEnd end = session_->Ended();
        const char* outcome = end == XrSessionEnd::Exited         ? "exited"
                              : end == XrSessionEnd::SessionLost  ? "session lost"
                              : end == XrSessionEnd::InstanceLost ? "instance lost"
                                                                  : "stopped";
        nlohmann::json gazeFrames = nlohmann::json::object();
        for (const auto& [name, n] : source_->FramesPerGazeSource()) gazeFrames[name] = n;
        nlohmann::json manifest;
        manifest["command"] = "xr";
        manifest["complete"] = end == XrSessionEnd::Exited;
        manifest["outcome"] = outcome;
        manifest["build"] = BuildInfoJson();
        manifest["config"] = ConfigToJson(config_);
        manifest["runtime"] = {{"name", connection_->runtimeName()},
                               {"system", connection_->systemName()},
                               {"eye_gaze_supported", connection_->eyeGazeSupported()},
                               {"swapchain", {{"width", swapchains_[0]->width()},
                                              {"height", swapchains_[0]->height()},
                                              {"vk_format", int(swapchains_[0]->format())}}}};
        manifest["session_states"] = session_->StatesSeen();
        manifest["frames"] = {{"ended", session_->FramesEnded()},
                              {"with_layer", session_->FramesWithLayers()},
                              {"rendered", loop_->FramesRendered()},
                              {"submitted", submitted_},
                              {"records", "frames.jsonl"}};
        manifest["gaze_source_frames"] = gazeFrames;
        manifest["gaze_fallback"] = source_->FallbackName();
        // Messages sent to fovrt's XR_EXT_debug_utils messenger (a runtime's or a layer's; Debian's
        // 1.0.20 core validation layer writes its report to a file instead).
        manifest["validation"] = {{"openxr_debug_utils", connection_->debugUtils()},
                                  {"openxr_messenger_errors", connection_->validationErrors()},
                                  {"openxr_messenger_warnings", connection_->validationWarnings()},
                                  {"vulkan_enabled", context_->validationEnabled()},
                                  {"vulkan_errors", context_->validationErrors()}};
        manifest["timing"] = stats_->SummaryJson();
        if (auto recording = wiring_->RecordedTo()) manifest["recorded_to"] = recording->string();
        WriteTextAtomically(outDir_ / "manifest.json", manifest.dump(2) + "\n");

        std::string gazeLine;
        for (const auto& [name, n] : source_->FramesPerGazeSource())
            gazeLine += fmt::format("{}{} {}", gazeLine.empty() ? "" : ", ", name, n);
        std::fprintf(stderr, "fovrt xr: %s\n", stats_->Summary().c_str());
        std::fprintf(stderr, "fovrt xr: %s after %llu frames ended (%llu with a layer); gaze frames: %s; "
                             "manifest %s\n",
                     outcome, (unsigned long long)session_->FramesEnded(),
                     (unsigned long long)session_->FramesWithLayers(), gazeLine.empty() ? "none" : gazeLine.c_str(),
                     (outDir_ / "manifest.json").string().c_str());
        if (context_->validationEnabled())
            std::fprintf(stderr, "fovrt xr: %u Vulkan validation errors, %u warnings\n", context_->validationErrors(),
                         context_->validationWarnings());
        if (end == XrSessionEnd::SessionLost)
            Fail("the OpenXR runtime lost the session (LOSS_PENDING) after {} frames; the recording holds the "
                 "frames rendered so far",
                 submitted_);
        if (end == XrSessionEnd::InstanceLost)
            Fail("the OpenXR runtime went away (instance lost) after {} frames; the recording holds the frames "
                 "rendered so far",
                 submitted_);
    }

    // Members die in reverse order: the render stages, the XR objects, the instance, then the
    // Vulkan device the runtime created (as hello_xr orders it), the window last.
    RunConfig config_;
    XrOptions options_;
    std::optional<PreviewWindow> window_;
    std::optional<VulkanContext> context_;
    std::optional<XrMirror> mirror_;
    std::unique_ptr<XrConnection> connection_;
    std::optional<XrHeadsetSession> session_;
    std::optional<XrEyeGaze> gaze_;
    std::array<std::optional<XrEyeSwapchain>, 2> swapchains_;
    std::optional<XrEyeImageWriter> writer_;
    std::optional<XrFrameSource> source_;
    std::optional<TrackedFrameSource> tracked_;
    std::optional<LiveStats> stats_;
    std::optional<LiveSessionWiring> wiring_;  // its hooks run on the render thread: outlives the loop
    std::optional<LiveLoop> loop_;
    fs::path outDir_;
    std::FILE* frameLog_ = nullptr;
    std::shared_ptr<const LiveFrame> last_;
    std::vector<XrCompositionLayerProjectionView> lastLayer_;  // the last frame's layer views
    uint64_t submitted_ = 0;   // frames submitted for the first time
    bool loopStarted_ = false; // --async: the render thread runs
    std::optional<XrTime> firstDisplayTime_;
    bool warnedInactive_ = false;
    double waitMs_ = 0.0;  // xrWaitFrame + xrBeginFrame of the current frame
    LiveClock::time_point start_;
};

}  // namespace

void RunXr(const RunConfig& config, const XrOptions& options) {
    // Before anything large is allocated (the same model as `fovrt run`; every listed variant counted).
    EnforceRunBudget(config, "xr");
    XrApp app(config, options);
    app.Run();
}

}  // namespace fovrt
