// XrMirror: `fovrt xr --mirror`, the desktop window (src/ui, as the preview's) showing what the headset
// gets — both eyes as submitted, the gaze marker and fovea outline, and the preview's panel with
// the headset's state in place of the mouse and fly-camera controls. It presents on the Vulkan
// device the runtime created, from the session's thread, after each xrEndFrame.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "live/live_loop.h"
#include "live/live_stats.h"
#include "ui/imgui_layer.h"
#include "ui/key_queue.h"
#include "ui/live_display.h"
#include "ui/preview_panel.h"
#include "ui/vulkan_window.h"

namespace fovrt {

struct XrOptions;

class XrMirror {
public:
    XrMirror(PreviewWindow& window, VulkanContext& context, const XrOptions& options);
    ~XrMirror();
    XrMirror(const XrMirror&) = delete;
    XrMirror& operator=(const XrMirror&) = delete;

    bool Closed() const;
    // The panel's eye-tracker controls act on `tracker` (the session's tracker model).
    void SetTracker(TrackedFrameSource* tracker) { panel_.tracker = tracker; }
    // Polls the window's input and presents `frame` (null: background) with the panel; at most
    // 60 times a second while the headset idles.
    void Present(LiveLoop& loop, LiveStats& stats, const std::shared_ptr<const LiveFrame>& frame,
                 std::vector<std::string> sessionLines);

private:
    PreviewWindow& window_;
    KeyQueue keys_;  // before ImGui, which chains to its key callback
    std::optional<LiveFrameDisplay> display_;
    std::optional<ImGuiLayer> imgui_;
    PanelState panel_;
    bool panelShown_ = true;
    LiveClock::time_point lastPresent_{};
    std::string screenshot_;  // --screenshot: the window as presented with the last of --frames
    uint64_t frames_ = 0;
};

}  // namespace fovrt
