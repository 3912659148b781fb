// `fovrt xr`: a headset session through OpenXR (SPEC §11). Each frame, in step with the runtime:
//   xrWaitFrame -> xrBeginFrame -> xrLocateViews + eye gaze at the predicted display time ->
//   spp maps -> path tracer -> denoiser (Vulkan, on the device the runtime created) ->
//   display pass into each eye's swapchain image -> xrEndFrame with one projection layer.
// By default the frame is rendered between xrBeginFrame and xrEndFrame with the poses located for
// its own display time; with `async` the live loop renders on its own thread from the newest
// located views while the session thread submits the newest finished frame every display slot.
// Either way every submitted layer carries the exact poses its pixels were traced from.
#pragma once

#include <cstdint>
#include <string>

#include "config/config.h"
#include "live/live_session.h"
#include "ui/vulkan_window.h"

namespace fovrt {

struct XrOptions {
    uint64_t frames = 0;         // frames rendered and submitted, then xrRequestExitSession (0: until Ctrl-C or the runtime stops)
    LiveSessionOptions session;  // --view, --write-inputs, --record, --stats (as `fovrt preview`)
    bool writeFrames = false;    // what each eye was sent, as PNG, in <output.dir>/xr/frames
    bool followPath = false;     // the scene camera's path carries the headset's origin along
    float speed = 1.0f;          // scene seconds per second of display time
    // Render on the live loop's own thread and submit the newest finished frame at every display
    // slot (with the poses it was traced from, for the compositor to reproject); otherwise each
    // frame is rendered between xrBeginFrame and xrEndFrame.
    bool async = false;
    bool mirror = false;         // the preview window shows what the headset gets, with its panel
    std::string screenshot;      // with --mirror and --frames: the window's last image (PNG)
    WindowOptions window;
};

// Runs the session until it exits. fovrt::Error (one line) when no session can start: no runtime,
// a bad XR_RUNTIME_JSON, no enable2, no HMD, an unsupported form factor; and when the runtime loses
// the session or the instance (the recording then holds the frames rendered so far).
void RunXr(const RunConfig& config, const XrOptions& options);

}  // namespace fovrt
