// TrackedFrameSource: the eye-tracker model (gaze/tracker.h) in a live session. It wraps the
// session's FrameSource (the preview's mouse or synthetic gaze, the headset's eye gaze), whose
// requests carry the TRUE gaze, keeps every true sample in a LiveGazeHistory on the live clock
// (each sample at its takenAt), and hands the frame on with
//   request.gaze      = what the tracker reports at the moment the frame starts (TrackedGaze over
//                       the history: rate, latency, noise, bias, dropouts, prediction) — the spp
//                       map follows it,
//   request.trueGaze  = the source's own sample for the frame (where the eye is).
// With an ideal tracker (the defaults) the frame passes through untouched, bit for bit, and
// trueGaze stays unset, as before the tracker model existed. The parameters may change at any
// time from any thread (the preview panel); they apply from the next frame.
// The history keeps what the current parameters read (TrackerLookbackSeconds): after a latency
// is raised, the tracked gaze holds the oldest kept sample until the new delay has passed.
#pragma once

#include <mutex>

#include "gaze/live_gaze_history.h"
#include "gaze/tracker.h"
#include "live/frame_source.h"

namespace fovrt {

class TrackedFrameSource final : public FrameSource {
public:
    // `inner` must outlive this. Throws fovrt::Error naming a bad gaze.tracker_* key.
    TrackedFrameSource(FrameSource& inner, const TrackerParams& params);

    SourcedFrame Next(uint32_t frame, double sceneTime) override;
    // What Next does to the inner source's frame, with the frame starting at `now` (for tests).
    void Track(SourcedFrame& frame, LiveClock::time_point now);

    TrackerParams Params() const;
    // fovrt::Error names a bad gaze.tracker_* / gaze.prediction key (the running ones stay).
    void SetParams(const TrackerParams& params);

private:
    double Seconds(LiveClock::time_point t) const;

    FrameSource& inner_;
    LiveClock::time_point epoch_;  // the tracker's time 0
    LiveGazeHistory history_;      // the render thread's alone
    mutable std::mutex mutex_;
    TrackerParams params_;
};

}  // namespace fovrt
