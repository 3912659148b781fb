// The live window panel's eye-tracker section: the tracker model (gaze/tracker.h) between the
// true gaze and the spp map, changed live — rate, latency, noise and prediction, over the ranges
// the config accepts — and what the overlay's two markers mean.
#pragma once

#include <string>

#include "live/tracked_frame_source.h"

namespace fovrt {

// `refused`: the message of the last change the tracker refused (kept across frames by the caller).
void DrawTrackerControls(TrackedFrameSource& tracker, std::string& refused);

}  // namespace fovrt
