// The tracker model in a live session (live/tracked_frame_source.h): with the default (ideal)
// tracker every frame passes through bit for bit, with no true gaze set (as before the model);
// with a latency the spp maps' gaze follows a pointer step exactly `latency` after the sample that
// saw it, while the true gaze is the source's own sample; bad parameters are refused by key and
// the running ones stay.
#include "core/error.h"
#include "live/tracked_frame_source.h"
#include "gaze_test_support.h"
#include "test_support.h"

using namespace fovrt;
using namespace std::chrono_literals;

namespace {

// A pointer the test moves: each frame carries the samples taken since the previous one.
class PointerSource final : public FrameSource {
public:
    void Move(const vec3& direction, LiveClock::time_point at, double seconds) {
        pending_.push_back(TimedGaze{GazeSample{seconds, direction, true}, at});
        newest_ = pending_.back();
    }
    SourcedFrame Next(uint32_t frame, double sceneTime) override {
        SourcedFrame out;
        out.request.frame = frame;
        out.request.timeSeconds = sceneTime;
        out.request.gaze = newest_.gaze;
        out.gazeTakenAt = newest_.takenAt;
        out.gazeSamples = std::move(pending_);
        pending_.clear();
        return out;
    }

private:
    TimedGaze newest_;
    std::vector<TimedGaze> pending_;
};

const vec3 kLeft = GazeDirectionFromAngles(-10.0f, 0.0f), kRight = GazeDirectionFromAngles(12.0f, 3.0f);

}  // namespace

TEST_CASE("live tracker: the ideal tracker leaves every frame as the source made it", "[live]") {
    PointerSource pointer;
    TrackedFrameSource tracked(pointer, TrackerParams{});
    const auto start = LiveClock::now();
    for (uint32_t f = 0; f < 50; ++f) {
        const auto at = start + f * 7ms;
        pointer.Move(GazeDirectionFromAngles(float(f) - 25.0f, 0.5f * float(f)), at, 0.007 * f);
        PointerSource copy = pointer;
        const SourcedFrame expected = copy.Next(f, f / 90.0);
        SourcedFrame frame = pointer.Next(f, f / 90.0);
        tracked.Track(frame, at + 3ms);
        CHECK(test::SameGazeBits(frame.request.gaze, expected.request.gaze));
        CHECK(!frame.request.trueGaze);
    }
}

TEST_CASE("live tracker: a pointer step reaches the spp maps' gaze exactly latency later", "[live]") {
    PointerSource pointer;
    TrackerParams params;
    params.latencyMs = 50.0;
    TrackedFrameSource tracked(pointer, params);
    const auto start = LiveClock::now();
    pointer.Move(kLeft, start, 0.0);
    SourcedFrame frame = pointer.Next(0, 0.0);
    tracked.Track(frame, start + 1ms);
    // The session's first sample (through the tracker's angles: equal to float rounding).
    CHECK(AngleBetweenDeg(frame.request.gaze.direction, frame.request.trueGaze->direction) < 1e-3f);
    const auto step = start + 100ms;
    pointer.Move(kRight, step, 0.1);
    const std::pair<std::chrono::microseconds, vec3> frames[] = {
        {100us, kLeft}, {20ms, kLeft}, {49999us, kLeft}, {50001us, kRight}, {80ms, kRight}};
    uint32_t index = 1;
    for (const auto& [after, expected] : frames) {
        INFO("frame " << index << ", " << after.count() << " us after the step");
        frame = pointer.Next(index, 0.1);
        tracked.Track(frame, step + after);
        REQUIRE(frame.request.trueGaze);
        CHECK(frame.request.trueGaze->direction == kRight);  // the source's own sample, bit for bit
        CHECK(AngleBetweenDeg(frame.request.gaze.direction, expected) < 1e-3f);
        CHECK(frame.request.gaze.timeSeconds == frame.request.trueGaze->timeSeconds);
        ++index;
    }
}

TEST_CASE("live tracker: refused parameters name the key and keep the running ones", "[live]") {
    PointerSource pointer;
    TrackerParams params;
    params.latencyMs = 20.0;
    TrackedFrameSource tracked(pointer, params);
    TrackerParams bad = params;
    bad.prediction = "cv";  // without a rate
    CHECK_THROWS_WITH(tracked.SetParams(bad), Catch::Contains("gaze.prediction: 'cv' needs gaze.tracker_rate_hz"));
    CHECK(tracked.Params().prediction == "none");
    bad.rateHz = 120.0;
    tracked.SetParams(bad);
    CHECK(tracked.Params().prediction == "cv");
    params.latencyMs = -1.0;
    CHECK_THROWS_WITH(TrackedFrameSource(pointer, params), Catch::Contains("gaze.tracker_latency_ms: -1 is out of range"));
}
