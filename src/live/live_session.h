// LiveSessionWiring: what both live apps (`fovrt preview`, `fovrt xr`) attach to their LiveLoop
// from the options they share — the view shown first (`--view`, refused with the list of views),
// every frame's FrameInputs (`--write-inputs`) and the session recording (`--record`). Written
// once so the preview and the headset app cannot drift apart in what the options do.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/config.h"
#include "live/live_loop.h"
#include "session/session_record.h"

namespace fovrt {

struct LiveSessionOptions {
    std::string view = "denoised";  // --view: a view of the first denoiser (LiveLoop::ViewNames)
    bool writeInputs = false;       // --write-inputs: FrameInputs + spp map EXRs per frame and eye in <output.dir>/inputs
    std::string record;             // --record: the session recording (session/session_record.h); "" none
    std::string stats;              // --stats: per-frame timings and latency, JSON Lines; "" none
};

// Throws fovrt::Error "--view V: not a view of denoiser D (views: a, b, …)" when `view` is not
// one of `views`.
void CheckViewName(const std::string& view, const std::vector<std::string>& views, const std::string& denoiser);

// The Vulkan device a live session presents on: the configured one, and "auto" where the
// denoiser runs as the C++ reference (denoise.device = cpu), since the window or headset still
// needs a device.
std::string LiveDisplayDevice(const RunConfig& config);

class LiveSessionWiring {
public:
    // Checks and sets the view, and hooks the inputs and the recording onto `loop` (before its
    // Start). The recording opens at the first rendered frame, so a session that never renders
    // leaves none; its header holds the loop's config, the build and `recordingHeader`'s members
    // (the app's: e.g. the OpenXR runtime). Must outlive the loop's render thread.
    LiveSessionWiring(LiveLoop& loop, const LiveSessionOptions& options,
                      nlohmann::json recordingHeader = nlohmann::json::object());
    LiveSessionWiring(const LiveSessionWiring&) = delete;
    LiveSessionWiring& operator=(const LiveSessionWiring&) = delete;

    // After the loop has stopped: the recording, complete. Idempotent.
    void Close();
    // The recording's file once a frame was recorded, else nullopt.
    std::optional<std::filesystem::path> RecordedTo() const;

private:
    std::optional<SessionRecorder> recorder_;
};

}  // namespace fovrt
