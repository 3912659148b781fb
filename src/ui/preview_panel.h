// The preview's ImGui panel: the live controls (denoiser, view, layout and overlay, foveation,
// gaze, head, pause / step / speed) and what the session measures (frame time split, per-pass
// plot, latency, rays per second, the running denoiser's memory table).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "display/display_compose.h"
#include "live/live_loop.h"
#include "live/live_stats.h"
#include "live/tracked_frame_source.h"
#include "ui/preview_source.h"

struct GLFWwindow;

namespace fovrt {

struct PanelState {
    DisplaySettings display;
    bool requestCapture = false;  // "save" pressed (as F12)
    bool requestReturnToPath = false;
    std::string title = "fovrt preview";
    // A headset session's state (runtime, session state, gaze source, frame counts), shown in
    // place of the gaze and head controls when there is no PreviewFrameSource.
    std::vector<std::string> sessionLines;
    TrackedFrameSource* tracker = nullptr;  // the eye-tracker model's controls (null: none shown)
    std::string trackerRefused;             // their last refused change
};

// source: null in a headset session (the headset gives the head and the gaze).
void DrawPreviewPanel(LiveLoop& loop, PreviewFrameSource* source, const LiveStats& stats,
                      const std::shared_ptr<const LiveFrame>& shown, const std::string& presentMode,
                      PanelState& state);

// The keys every live window shares: Space pause, Tab the panel, O the overlay, L the layout,
// V the next view, 1–9 a denoiser, Esc closes the window. False for any other key.
bool HandleLiveWindowKey(int key, LiveLoop& loop, GLFWwindow* window, PanelState& state, bool& panelShown);

}  // namespace fovrt
