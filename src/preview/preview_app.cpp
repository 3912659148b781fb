#include "preview/preview_app.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include "core/error.h"
#include "io/exr.h"
#include "io/png.h"
#include "live/live_loop.h"
#include "live/live_session.h"
#include "live/live_stats.h"
#include "pipeline/denoiser_set.h"
#include "ui/imgui_layer.h"
#include "ui/key_queue.h"
#include "ui/live_display.h"
#include "ui/preview_panel.h"
#include "ui/preview_source.h"
#include "ui/vulkan_window.h"
#include "live/tracked_frame_source.h"

namespace fovrt {
namespace {

namespace fs = std::filesystem;

// F12: the shown window image, and per eye the frame's FrameInputs, spp map and denoised output
// in one multi-layer EXR.
void SaveFrame(const fs::path& dir, const LiveFrame& frame, const Plane<uint32_t>& window) {
    fs::create_directories(dir);
    const std::string stem = fmt::format("frame{:06d}", frame.number);
    WriteWindowCapturePng(dir / (stem + "_window.png"), window);
    for (int eye = 0; eye < 2; ++eye) {
        const EyeFrame& e = frame.stereo.eyes[size_t(eye)];
        WriteFrameInputsExr(dir / fmt::format("{}_{}.exr", stem, eye == 0 ? "left" : "right"), e.inputs,
                            e.sppMap, {ExrLayer::FromPlane("denoised", frame.denoised[size_t(eye)])});
    }
    std::fprintf(stderr, "fovrt preview: saved frame %llu to %s/%s_*\n", (unsigned long long)frame.number,
                 dir.string().c_str(), stem.c_str());
}

// The pointer as a head-space gaze direction: through whichever eye image it is over.
std::optional<vec3> PointerGaze(GLFWwindow* window, const DisplaySettings& display, ivec2 eyeSize,
                                const std::array<EyeCamera, 2>& eyes) {
    double x = 0, y = 0;
    glfwGetCursorPos(window, &x, &y);
    int ww = 0, wh = 0, fw = 0, fh = 0;
    glfwGetWindowSize(window, &ww, &wh);
    glfwGetFramebufferSize(window, &fw, &fh);
    if (ww <= 0 || wh <= 0 || fw <= 0 || fh <= 0 || eyeSize.x <= 0) return std::nullopt;
    // window coordinates -> framebuffer pixels (they differ on high-DPI displays)
    const vec2 p(float(x) * float(fw) / float(ww), float(y) * float(fh) / float(wh));
    const auto viewports = DisplayViewports(display.layout, eyeSize, ivec2(fw, fh));
    for (int slot = 0; slot < 2; ++slot) {
        const DisplayViewport& v = viewports[size_t(slot)];
        if (v.extent.x <= 0) continue;
        const vec2 local = (p - vec2(v.origin)) / vec2(v.extent);
        if (local.x < 0 || local.y < 0 || local.x >= 1 || local.y >= 1) continue;
        const int eye = display.layout == DisplayLayout::RightEye ? 1 : slot;
        const EyeCamera& camera = eyes[size_t(eye)];
        if (camera.width() == 0) return std::nullopt;
        // eye space = head space orientation (parallel eye axes: gaze/gaze_source.h)
        return camera.EyeDirection(local * vec2(camera.width(), camera.height()));
    }
    return std::nullopt;
}

class PreviewSession {
public:
    PreviewSession(const RunConfig& config, const PreviewOptions& options)
        : config_(config), options_(options), window_(options.window),
          context_(VulkanContext::Create(window_.ContextOptions(LiveDisplayDevice(config)))),
          attachment_(window_, context_), keys_(window_.handle()), source_(config),
          tracked_(source_, config.gaze.tracker), stats_(options.session.stats) {
        display_.emplace(context_);
        imgui_.emplace(window_, context_);
        panelShown_ = options.panel;
        panel_.display.layout = options.layout;
        panel_.display.overlay = options.overlay;
        panel_.display.exposure = config.output.exposure;
        panel_.display.byteOrder = window_.ByteOrder();
        panel_.tracker = &tracked_;
        loop_.emplace(config, &context_, tracked_);
        source_.Bind(loop_->Pipeline());
        wiring_.emplace(*loop_, options.session);
    }

    // Members die in reverse order, also when the constructor throws: the render thread first,
    // then ImGui (it idles the queue), the display pass, the window's swapchain, the context.

    void Run() {
        std::fprintf(stderr, "fovrt preview: scene '%s', %d×%d per eye, denoiser %s on %s, present %s, %s%s\n",
                     loop_->Pipeline().GetScene().name.c_str(), config_.camera.width, config_.camera.height,
                     loop_->Controls().denoiser.c_str(), context_.deviceName().c_str(), window_.PresentModeName(),
                     options_.pipelined ? "pipelined (trace N+1 while denoising N)" : "serial", options_.frames ? fmt::format(", {} frames", options_.frames).c_str() : "");
        glfwPollEvents();
        HandleInput(0.0);  // the first frame already sees the pointer
        loop_->Start(options_.frames, options_.pipelined);
        auto lastPresent = LiveClock::now() - std::chrono::seconds(1);
        auto lastInput = LiveClock::now();
        auto lastPoll = LiveClock::now();
        std::optional<LiveClock::time_point> lastShown;  // when the last of --frames was presented
        while (!window_.ShouldClose()) {
            // Wake at up to 60 Hz: new frames, input and the panel; sleeping the rest leaves the
            // cores to the path tracer.
            glfwWaitEventsTimeout(1.0 / 60.0);
            const auto now = LiveClock::now();
            const double dt = std::min(0.1, MsBetween(lastPoll, now) * 1e-3);
            lastPoll = now;
            if (HandleInput(dt)) lastInput = now;
            if (auto error = loop_->Error()) Fail("render thread: {}", *error);

            std::shared_ptr<const LiveFrame> latest = loop_->Latest();
            const bool newFrame = latest && latest->number != presentedNumber_;
            const bool lastFrame = options_.frames && latest && latest->number >= options_.frames;
            const bool busy = MsBetween(lastInput, now) < 500.0 || MsBetween(lastPresent, now) > 100.0;
            if (!newFrame && !busy && !captureRequested_) continue;
            const bool capture = captureRequested_ || (lastFrame && newFrame && !options_.screenshot.empty());
            if (!Present(latest, capture)) continue;
            lastPresent = LiveClock::now();
            if (lastFrame && newFrame) lastShown = lastPresent;
            if (lastShown && MsBetween(*lastShown, lastPresent) >= options_.lingerSeconds * 1e3) break;
        }
        loop_->Stop();
        window_.WaitIdle();
        wiring_->Close();
        if (auto error = loop_->Error()) Fail("render thread: {}", *error);
        std::fprintf(stderr, "fovrt preview: %s (%llu frames rendered)\n", stats_.Summary().c_str(),
                     (unsigned long long)loop_->FramesRendered());
        if (context_.validationEnabled())
            std::fprintf(stderr, "fovrt preview: %u Vulkan validation errors, %u warnings\n",
                         context_.validationErrors(), context_.validationWarnings());
        if (options_.frames && presentedNumber_ < options_.frames)
            std::fprintf(stderr, "fovrt preview: the window was closed after %llu of %llu frames\n",
                         (unsigned long long)presentedNumber_, (unsigned long long)options_.frames);
    }

private:
    // Returns whether there was input this iteration.
    bool HandleInput(double dt) {
        GLFWwindow* w = window_.handle();
        bool input = !keys_.Empty();
        const bool keyboard = !imgui_->WantsKeyboard();
        while (std::optional<int> key = keys_.Pop())
            if (keyboard || *key == GLFW_KEY_F12) HandleKey(*key);
        // Fly camera: WASD + Q/E move, right-drag turns; the first move leaves the camera path.
        if (keyboard) {
            vec3 move(0.0f);
            if (glfwGetKey(w, GLFW_KEY_W) == GLFW_PRESS) move.z -= 1;
            if (glfwGetKey(w, GLFW_KEY_S) == GLFW_PRESS) move.z += 1;
            if (glfwGetKey(w, GLFW_KEY_A) == GLFW_PRESS) move.x -= 1;
            if (glfwGetKey(w, GLFW_KEY_D) == GLFW_PRESS) move.x += 1;
            if (glfwGetKey(w, GLFW_KEY_E) == GLFW_PRESS) move.y += 1;
            if (glfwGetKey(w, GLFW_KEY_Q) == GLFW_PRESS) move.y -= 1;
            if (move != vec3(0.0f)) {
                FlyCamera camera = FreeOrPath();
                camera.Move(move * float(options_.flySpeed * dt));
                source_.SetFreeHead(camera);
                input = true;
            }
        }
        double x = 0, y = 0;
        glfwGetCursorPos(w, &x, &y);
        const bool right = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS && !imgui_->WantsMouse();
        if (right && dragging_) {
            FlyCamera camera = FreeOrPath();
            camera.Turn(-float(x - dragX_) * 0.003f, -float(y - dragY_) * 0.003f);
            source_.SetFreeHead(camera);
            input = true;
        }
        dragging_ = right;
        dragX_ = x;
        dragY_ = y;
        // The mouse gaze: polled every iteration, so the request takes the newest position.
        if (source_.MouseGaze() && !imgui_->WantsMouse()) {
            const ivec2 eyeSize(config_.camera.width, config_.camera.height);
            if (auto gaze = PointerGaze(w, panel_.display, eyeSize, source_.LatestEyes()))
                source_.SetPointerGaze(*gaze, LiveClock::now());
        }
        if (panel_.requestReturnToPath) {
            source_.SetFreeHead(std::nullopt);
            panel_.requestReturnToPath = false;
        }
        return input;
    }

    FlyCamera FreeOrPath() const {
        if (auto free = source_.FreeHead()) return *free;
        const auto latest = loop_->Latest();
        return FlyCamera::FromPose(source_.HeadAt(latest ? latest->source.request.timeSeconds : 0.0));
    }

    void HandleKey(int key) {
        if (HandleLiveWindowKey(key, *loop_, window_.handle(), panel_, panelShown_)) return;
        switch (key) {
            case GLFW_KEY_N: loop_->Step(); break;
            case GLFW_KEY_F12: captureRequested_ = true; break;
            case GLFW_KEY_G:
                source_.SetGazeSource(source_.MouseGaze() ? source_.SyntheticDefault() : "mouse");
                break;
            case GLFW_KEY_C: source_.SetFreeHead(std::nullopt); break;
            default: break;
        }
    }

    // Composes and presents; false when the swapchain had to be rebuilt (nothing presented).
    bool Present(const std::shared_ptr<const LiveFrame>& latest, bool capture) {
        const auto start = LiveClock::now();
        std::optional<PreviewWindow::Frame> frame = window_.BeginFrame();
        if (!frame) return false;
        imgui_->NewFrame();
        if (panelShown_)
            DrawPreviewPanel(*loop_, &source_, stats_, latest, window_.PresentModeName(), panel_);
        if (panel_.requestCapture) {
            captureRequested_ = true;
            capture = true;
            panel_.requestCapture = false;
        }
        display_->Record(latest, panel_.display, *frame);
        imgui_->Render(*frame, window_.OverlayRenderPass());
        window_.EndFrame(*frame, capture);
        const auto presented = LiveClock::now();
        const double presentMs = MsBetween(start, presented);
        stats_.AddDisplayFrame(presentMs);
        if (latest && latest->number != presentedNumber_) {
            presentedNumber_ = latest->number;
            stats_.Add({latest->number, MsBetween(latest->source.gazeTakenAt, presented), presentMs,
                        latest->timings});
        }
        if (capture) {
            std::optional<Plane<uint32_t>> pixels = window_.TakeCapture();
            if (pixels && captureRequested_ && latest) {
                const fs::path dir = options_.captureDir.empty() ? fs::path(config_.output.dir) / "captures"
                                                                 : fs::path(options_.captureDir);
                SaveFrame(dir, *latest, *pixels);
            }
            if (pixels && !options_.screenshot.empty() && options_.frames && latest &&
                latest->number >= options_.frames)
                WriteWindowCapturePng(options_.screenshot, *pixels);
            captureRequested_ = false;
        }
        return true;
    }

    // The window's swapchain on the context, released before the context goes.
    struct Attachment {
        PreviewWindow& window;
        Attachment(PreviewWindow& w, VulkanContext& context) : window(w) { w.AttachVulkan(context); }
        ~Attachment() { window.DetachVulkan(); }
        Attachment(const Attachment&) = delete;
        Attachment& operator=(const Attachment&) = delete;
    };

    RunConfig config_;
    PreviewOptions options_;
    PreviewWindow window_;
    VulkanContext context_;
    Attachment attachment_;
    KeyQueue keys_;  // before ImGui, which chains to its key callback
    PreviewFrameSource source_;
    TrackedFrameSource tracked_;  // the eye-tracker model over source_'s true gaze
    LiveStats stats_;
    std::optional<LiveFrameDisplay> display_;
    std::optional<ImGuiLayer> imgui_;
    std::optional<LiveSessionWiring> wiring_;  // its hooks run on the render thread: outlives the loop
    std::optional<LiveLoop> loop_;
    PanelState panel_;
    bool panelShown_ = true;
    bool captureRequested_ = false;
    bool dragging_ = false;
    double dragX_ = 0, dragY_ = 0;
    uint64_t presentedNumber_ = 0;
};

}  // namespace

void RunPreview(const RunConfig& config, const PreviewOptions& options) {
    // Before anything large is allocated (the same model as `fovrt run`; every listed variant counted).
    EnforceRunBudget(config, "preview");
    PreviewSession session(config, options);
    session.Run();
}

}  // namespace fovrt
