// LiveFrameDisplay: a LiveFrame on a live window — the display pass (display/display_pass.h) fed
// with both eyes of the newest frame (uploaded once per frame) and their gaze marks, composed into
// the window's swapchain image. The preview and the headset's mirror window present through it.
#pragma once

#include <cstdint>
#include <memory>

#include "display/display_pass.h"
#include "live/live_loop.h"
#include "ui/vulkan_window.h"

namespace fovrt {

class LiveFrameDisplay {
public:
    explicit LiveFrameDisplay(VulkanContext& context) : pass_(context) {}

    // Whether `frame` is not the one whose eyes were uploaded last.
    bool IsNew(const std::shared_ptr<const LiveFrame>& frame) const { return frame && frame->number != uploaded_; }
    // Records into `target`'s command buffer: the upload of `frame`'s eyes when new, the
    // composition with `settings` (its mode set from the frame's view: HDR or display-ready) and
    // the copy into the swapchain image. A null frame composes the background.
    void Record(const std::shared_ptr<const LiveFrame>& frame, DisplaySettings& settings,
                const PreviewWindow::Frame& target);

private:
    DisplayPass pass_;
    uint64_t uploaded_ = 0;
};

}  // namespace fovrt
