#include "xr/xr_mirror.h"

#include <GLFW/glfw3.h>

#include "preview/overlay_marks.h"
#include "xr/xr_app.h"

namespace fovrt {
namespace {

std::deque<int>& PendingKeys(GLFWwindow* window) {
    return *static_cast<std::deque<int>*>(glfwGetWindowUserPointer(window));
}

void OnKey(GLFWwindow* window, int key, int, int action, int) {
    if (action == GLFW_PRESS) PendingKeys(window).push_back(key);
}

}  // namespace

XrMirror::XrMirror(PreviewWindow& window, VulkanContext& context, const XrOptions& options) : window_(window) {
    window.AttachVulkan(context);
    glfwSetWindowUserPointer(window.handle(), &keys_);
    glfwSetKeyCallback(window.handle(), OnKey);  // before ImGui, which chains to it
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
    while (!keys_.empty()) {
        const int key = keys_.front();
        keys_.pop_front();
        if (keyboard) HandleLiveWindowKey(key, loop, window_.handle(), panel_, panelShown_);
    }
    const auto now = LiveClock::now();
    const bool fresh = frame && frame->number != uploaded_;
    if (!fresh && now - lastPresent_ < std::chrono::milliseconds(16)) return;
    std::optional<PreviewWindow::Frame> target = window_.BeginFrame();
    if (!target) return;
    lastPresent_ = now;
    imgui_->NewFrame();
    panel_.sessionLines = std::move(sessionLines);
    if (panelShown_) DrawPreviewPanel(loop, nullptr, stats, frame, "headset-paced", panel_);
    if (frame) {
        if (fresh) {
            display_->SetEyes(frame->shown[0].rgb, frame->shown[1].rgb, OverlayMarks(*frame));
            uploaded_ = frame->number;
        }
        panel_.display.mode = frame->shown[0].hdr ? DisplayMode::Hdr : DisplayMode::Display;
    }
    display_->Record(target->cmd, panel_.display, int(target->extent.width), int(target->extent.height));
    const VkBufferImageCopy region = display_->OutputCopyRegion();
    vkCmdCopyBufferToImage(target->cmd, display_->Output().handle(), target->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           1, &region);
    imgui_->Render(*target, window_.OverlayRenderPass());
    const bool capture = fresh && !screenshot_.empty() && frames_ && frame->number >= frames_;
    window_.EndFrame(*target, capture);
    stats.AddDisplayFrame(0.0);
    if (capture)
        if (std::optional<Plane<uint32_t>> pixels = window_.TakeCapture()) WriteWindowCapturePng(screenshot_, *pixels);
}

}  // namespace fovrt
