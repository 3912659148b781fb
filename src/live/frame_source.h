// FrameSource: where a live session's frames come from — the head pose and each eye's camera,
// and the gaze. The desktop preview builds them from the mouse and a fly camera or the scene's
// camera path; the OpenXR session from xrLocateViews and eye tracking. The render thread asks for
// one request per frame, at the moment it starts the frame.
#pragma once

#include <chrono>
#include <vector>

#include "pipeline/frame_request.h"

namespace fovrt {

using LiveClock = std::chrono::steady_clock;

// Milliseconds from a to b (the loop's stage times, the apps' latencies).
inline double MsBetween(LiveClock::time_point a, LiveClock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

// A gaze sample with the wall-clock moment it was taken: gaze-to-photon latency runs from here.
// GazeSample::timeSeconds is the source's own clock: scene time for synthetic sources, seconds
// since the session started for the mouse (and an eye tracker).
struct TimedGaze {
    GazeSample gaze;
    LiveClock::time_point takenAt;
};

struct SourcedFrame {
    FrameRequest request;
    Pose head;                           // the head pose the eyes were placed from
    LiveClock::time_point gazeTakenAt;   // when request.gaze was sampled
    std::vector<TimedGaze> gazeSamples;  // every sample since the previous frame (recordings)
};

class FrameSource {
public:
    virtual ~FrameSource() = default;
    // The request for sequential frame `frame` at scene time `sceneTime`.
    virtual SourcedFrame Next(uint32_t frame, double sceneTime) = 0;
};

}  // namespace fovrt
