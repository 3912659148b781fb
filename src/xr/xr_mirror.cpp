#include "xr/xr_mirror.h"

#include <GLFW/glfw3.h>

#include "xr/xr_app.h"

namespace fovrt {

XrMirror::XrMirror(PreviewWindow& window, VulkanContext& context, const XrOptions& options)
    : window_(window), keys_(window.handle()) {
    window.AttachVulkan(context);
    display_.emplace(context);
    imgui_.emplace(window, context);
    panel_.title = "fovrt xr mirror";
    panel_.display.byteOrder = window.ByteOrder();
    screenshot_ = options.screenshot;
    frames_ = options.frames;
}

XrMirror::~XrMirror() {
    window_.WaitIdle();
    imgui_.reset();
    display_.reset();
    window_.DetachVulkan();
}

bool XrMirror::Closed() const { return window_.ShouldClose(); }

void XrMirror::Present(LiveLoop& loop, LiveStats& stats, const std::shared_ptr<const LiveFrame>& frame,
                       std::vector<std::string> sessionLines) {
    glfwPollEvents();
    const bool keyboard = !imgui_->WantsKeyboard();
    while (std::optional<int> key = keys_.Pop())
        if (keyboard) HandleLiveWindowKey(*key, loop, window_.handle(), panel_, panelShown_);
    const auto now = LiveClock::now();
    const bool fresh = display_->IsNew(frame);
    if (!fresh && now - lastPresent_ < std::chrono::milliseconds(16)) return;
    std::optional<PreviewWindow::Frame> target = window_.BeginFrame();
    if (!target) return;
    lastPresent_ = now;
    imgui_->NewFrame();
    panel_.sessionLines = std::move(sessionLines);
    if (panelShown_) DrawPreviewPanel(loop, nullptr, stats, frame, "headset-paced", panel_);
    display_->Record(frame, panel_.display, *target);
    imgui_->Render(*target, window_.OverlayRenderPass());
    const bool capture = fresh && !screenshot_.empty() && frames_ && frame->number >= frames_;
    window_.EndFrame(*target, capture);
    stats.AddDisplayFrame(0.0);
    if (capture)
        if (std::optional<Plane<uint32_t>> pixels = window_.TakeCapture()) WriteWindowCapturePng(screenshot_, *pixels);
}

}  // namespace fovrt
