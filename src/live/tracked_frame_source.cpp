#include "live/tracked_frame_source.h"

namespace fovrt {

TrackedFrameSource::TrackedFrameSource(FrameSource& inner, const TrackerParams& params)
    : inner_(inner), epoch_(LiveClock::now()), params_(params) {
    ValidateTrackerParams(params_);
}

TrackerParams TrackedFrameSource::Params() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return params_;
}

void TrackedFrameSource::SetParams(const TrackerParams& params) {
    ValidateTrackerParams(params);
    std::lock_guard<std::mutex> lock(mutex_);
    params_ = params;
}

double TrackedFrameSource::Seconds(LiveClock::time_point t) const {
    return std::chrono::duration<double>(t - epoch_).count();
}

SourcedFrame TrackedFrameSource::Next(uint32_t frame, double sceneTime) {
    SourcedFrame out = inner_.Next(frame, sceneTime);
    Track(out, LiveClock::now());
    return out;
}

void TrackedFrameSource::Track(SourcedFrame& frame, LiveClock::time_point now) {
    const TrackerParams params = Params();
    // Every true sample on one clock: the live clock's seconds when it was taken (the sources'
    // own timeSeconds differ: scene time for synthetic gaze, session time for the mouse).
    auto add = [&](GazeSample sample, LiveClock::time_point takenAt) {
        sample.timeSeconds = Seconds(takenAt);
        history_.Add(sample);
    };
    for (const TimedGaze& g : frame.gazeSamples) add(g.gaze, g.takenAt);
    add(frame.request.gaze, frame.gazeTakenAt);
    const double t = Seconds(now);
    history_.DropBefore(t - TrackerLookbackSeconds(params));
    if (IsIdealTracker(params)) return;

    const GazeSample truth = frame.request.gaze;
    GazeSample tracked = TrackedGaze(history_, params).At(t);
    tracked.timeSeconds = truth.timeSeconds;  // the frame's gaze time, on the source's clock
    frame.request.gaze = tracked;
    frame.request.trueGaze = truth;
}

}  // namespace fovrt
