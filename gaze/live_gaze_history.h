// LiveGazeHistory: the true gaze of a live session (mouse pointer, headset eye tracker) as a
// GazeSource. A live session sees its true gaze as samples arriving over time, while the tracker
// model (gaze/tracker.h: TrackedGaze) asks the true gaze at past times (capture = t − latency,
// earlier samples for prediction and blink detection). This keeps the samples, time-stamped on
// one clock, and answers At(t) with the newest sample taken at or before t — what a tracker
// capturing the eye at t would have seen — so the headless tracker model runs unchanged on live
// gaze.
//
// Not thread-safe: one thread adds and asks (a live session's render thread).
#pragma once

#include <deque>
#include <string>

#include "gaze/gaze_source.h"

namespace fovrt {

class LiveGazeHistory final : public GazeSource {
public:
    std::string Name() const override { return "live"; }
    // The newest sample with timeSeconds ≤ t, returned as it was added (bit for bit). Before the
    // first sample, the first (a session starts where its first sample looks); with no sample at
    // all, an invalid sample straight ahead.
    GazeSample At(double timeSeconds) const override;

    // Adds a sample taken at sample.timeSeconds. Samples come in time order: one at the newest
    // time replaces it (a later reading of the same instant), an older one is ignored (false).
    bool Add(const GazeSample& sample);
    // Forgets what At(t) can no longer return for t ≥ `oldest`: every sample before the newest
    // one taken at or before `oldest` (so memory stays flat in a long session).
    void DropBefore(double oldest);

    size_t Size() const { return samples_.size(); }
    bool Empty() const { return samples_.empty(); }

private:
    std::deque<GazeSample> samples_;  // timeSeconds increasing
};

}  // namespace fovrt
