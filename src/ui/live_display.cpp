#include "ui/live_display.h"

#include <array>

namespace fovrt {

void LiveFrameDisplay::Record(const std::shared_ptr<const LiveFrame>& frame, DisplaySettings& settings,
                              const PreviewWindow::Frame& target) {
    if (frame) {
        if (IsNew(frame)) {
            std::array<FoveaMark, 2> marks;
            for (int eye = 0; eye < 2; ++eye)
                marks[size_t(eye)] = {frame->gazePixel[size_t(eye)], frame->foveaRadiusPixels[size_t(eye)],
                                      frame->trueGazePixel[size_t(eye)]};
            pass_.SetEyes(frame->shown[0].rgb, frame->shown[1].rgb, marks);
            uploaded_ = frame->number;
        }
        settings.mode = frame->shown[0].hdr ? DisplayMode::Hdr : DisplayMode::Display;
    }
    pass_.Record(target.cmd, settings, int(target.extent.width), int(target.extent.height));
    const VkBufferImageCopy region = pass_.OutputCopyRegion();
    vkCmdCopyBufferToImage(target.cmd, pass_.Output().handle(), target.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &region);
}

}  // namespace fovrt
