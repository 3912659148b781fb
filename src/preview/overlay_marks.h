// The overlay a live window draws over a frame's eyes (live/display_compose.h): the gaze the spp
// map followed with its fovea outline, and, when the session runs a tracker model, the true gaze
// (LiveFrame::trueGazePixel), so the tracker's lag and error show between the two markers.
// Shared by the preview window and the headset's mirror window.
#pragma once

#include <array>

#include "live/display_compose.h"
#include "live/live_loop.h"

namespace fovrt {

inline std::array<FoveaMark, 2> OverlayMarks(const LiveFrame& frame) {
    std::array<FoveaMark, 2> marks;
    for (size_t eye = 0; eye < 2; ++eye)
        marks[eye] = {frame.gazePixel[eye], frame.foveaRadiusPixels[eye], frame.trueGazePixel[eye]};
    return marks;
}

}  // namespace fovrt
