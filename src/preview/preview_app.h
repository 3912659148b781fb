// The desktop mirror preview: a live session (live/live_loop.h) shown in a window. The window
// thread polls input, draws the panel and presents the newest finished frame; the render thread
// traces and denoises. `fovrt preview` (cmd_preview.cpp) parses the options.
#pragma once

#include <cstdint>
#include <string>

#include "config/config.h"
#include "display/display_compose.h"
#include "live/live_session.h"
#include "ui/vulkan_window.h"

namespace fovrt {

struct PreviewOptions {
    WindowOptions window;
    uint64_t frames = 0;          // render this many frames, show the last, exit (0: until closed)
    std::string screenshot;       // PNG of the last presented window image (the swapchain's pixels)
    std::string captureDir;       // where F12 writes (default: <output.dir>/captures)
    LiveSessionOptions session;   // --view, --write-inputs, --record, --stats (as `fovrt xr`)
    double lingerSeconds = 0.0;   // with frames: keep the last frame on screen this long
    DisplayLayout layout = DisplayLayout::SideBySide;
    bool overlay = true;
    bool panel = true;
    float flySpeed = 1.0f;        // metres per second
    bool pipelined = false;       // trace frame N+1 while denoising N (LiveLoop::Start)
};

// Runs the session until the window closes (or `frames` are done). fovrt::Error for bad input
// (no display, no surface support, a render-thread failure), with the recording left complete.
void RunPreview(const RunConfig& config, const PreviewOptions& options);

}  // namespace fovrt
