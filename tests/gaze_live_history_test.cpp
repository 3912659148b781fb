// The tracker model on live gaze (gaze/live_gaze_history.h): a live session's true gaze arrives
// as time-stamped samples; TrackedGaze over their history gives a step in the true gaze to the
// tracked gaze exactly `latency` after the first sample that saw it (at the tracker's rate), an
// ideal tracker passes the samples through bit for bit, and pruning to TrackerLookbackSeconds
// changes nothing the tracker reports.
#include <cmath>
#include "core/rng.h"
#include "gaze/live_gaze_history.h"
#include "gaze/tracker.h"
#include "gaze_test_support.h"
#include "test_support.h"

using namespace fovrt;

namespace {

vec2 Angles(const GazeSample& s) { return GazeAnglesFromDirection(s.direction); }

// A mouse polled every `period` seconds from t = 0 to `end`: yaw 0° until `stepAt`, 10° after.
LiveGazeHistory PolledStep(double period, double stepAt, double end) {
    LiveGazeHistory history;
    for (int i = 0; i * period <= end; ++i) {
        const double t = i * period;
        history.Add(GazeSample{t, GazeDirectionFromAngles(t < stepAt ? 0.0f : 10.0f, 0.0f), true});
    }
    return history;
}

}  // namespace

TEST_CASE("live gaze history: the newest sample at or before t, the first before it", "[gaze][tracker]") {
    LiveGazeHistory history;
    CHECK(!history.At(1.0).valid);  // nothing yet
    const GazeSample a{0.5, GazeDirectionFromAngles(1.0f, 2.0f), true};
    const GazeSample b{0.7, GazeDirectionFromAngles(3.0f, -1.0f), false};
    CHECK(history.Add(a));
    CHECK(history.Add(b));
    CHECK(test::SameGazeBits(history.At(0.1), a));  // before the first: the first
    CHECK(test::SameGazeBits(history.At(0.5), a));
    CHECK(test::SameGazeBits(history.At(0.6999), a));
    CHECK(test::SameGazeBits(history.At(0.7), b));
    CHECK(test::SameGazeBits(history.At(9.0), b));
    CHECK(!history.Add(GazeSample{0.6, vec3(0, 0, -1), true}));  // out of order: ignored
    CHECK(history.Size() == 2);
    const GazeSample c{0.7, GazeDirectionFromAngles(4.0f, 0.0f), true};
    CHECK(history.Add(c));  // the same instant read again: replaces
    CHECK(test::SameGazeBits(history.At(0.8), c));
    history.DropBefore(0.69);  // keeps a: At(0.69) still needs it
    CHECK(history.Size() == 2);
    history.DropBefore(0.75);
    CHECK(history.Size() == 1);
    CHECK(test::SameGazeBits(history.At(0.75), c));
}

TEST_CASE("live gaze history: an ideal tracker passes the live samples through bit for bit", "[gaze][tracker]") {
    Pcg32 rng(5);
    LiveGazeHistory history;
    for (int i = 0; i < 200; ++i)
        history.Add(GazeSample{0.003 * i + 0.001 * rng.NextFloat(),
                               GazeDirectionFromAngles(40.0f * rng.NextFloat() - 20.0f, 30.0f * rng.NextFloat() - 15.0f),
                               rng.NextFloat() > 0.1f});
    TrackerParams ideal;
    REQUIRE(IsIdealTracker(ideal));
    TrackedGaze tracked(history, ideal);
    for (double t = 0.0; t < 0.7; t += 0.0017) CHECK(test::SameGazeBits(tracked.At(t), history.At(t)));
}

TEST_CASE("live gaze history: a step reaches the tracked gaze exactly latency later, at the tracker's rate",
          "[gaze][tracker]") {
    // A pointer polled at 250 Hz; the step is first seen by the poll at 0.504 s.
    const double poll = 0.004, stepAt = 0.5021, seen = 0.504;
    const LiveGazeHistory history = PolledStep(poll, stepAt, 2.0);
    for (double rate : {0.0, 90.0, 120.0}) {
        for (double latencyMs : {0.0, 20.0, 80.0}) {
            if (rate == 0.0 && latencyMs == 0.0) continue;  // ideal: the pass-through above
            INFO("rate " << rate << " Hz, latency " << latencyMs << " ms");
            TrackerParams params;
            params.rateHz = rate;
            params.latencyMs = latencyMs;
            TrackedGaze tracked(history, params);
            // The tracker's first capture at or after the poll that saw the step, plus the latency.
            const double captured = rate > 0.0 ? std::ceil(seen * rate - 1e-9) / rate : seen;
            // (Without a rate: 1 ps past, so t − L is not an ulp early.)
            const double arrives = captured + latencyMs / 1000.0 + (rate == 0.0 ? 1e-12 : 0.0);
            CHECK(Angles(tracked.At(arrives - 1e-6)).x == Approx(0.0f).margin(1e-4));
            CHECK(Angles(tracked.At(arrives)).x == Approx(10.0f).margin(1e-4));
            CHECK(Angles(tracked.At(arrives + 0.3)).x == Approx(10.0f).margin(1e-4));
        }
    }
}

TEST_CASE("live gaze history: pruning to the tracker's lookback changes nothing it reports", "[gaze][tracker]") {
    // A random walk with saccades and invalid runs, polled at 500 Hz over 4 s; frames every 11 ms.
    Pcg32 rng(17);
    std::vector<GazeSample> samples;
    vec2 angles(0.0f);
    for (int i = 0; i < 2000; ++i) {
        const double t = 0.002 * i;
        angles += vec2(rng.NextFloat() - 0.5f, rng.NextFloat() - 0.5f) * (rng.NextFloat() < 0.01f ? 30.0f : 0.3f);
        angles = glm::clamp(angles, vec2(-30.0f), vec2(30.0f));
        const bool blink = std::fmod(t, 1.3) > 1.1;
        samples.push_back(GazeSample{t, GazeDirectionFromAngles(angles.x, angles.y), !blink});
    }
    TrackerParams landing;
    landing.rateHz = 120.0;
    landing.latencyMs = 40.0;
    landing.noiseDeg = 0.3f;
    landing.dropout = 0.05;
    landing.blinkMs = 150.0;
    landing.prediction = "landing";
    TrackerParams cv = landing;
    cv.prediction = "cv";
    cv.rateHz = 90.0;
    TrackerParams frameRate;
    frameRate.latencyMs = 120.0;
    frameRate.noiseDeg = 1.0f;
    for (const TrackerParams& params : {landing, cv, frameRate}) {
        INFO("rate " << params.rateHz << ", prediction " << params.prediction);
        LiveGazeHistory full, pruned;
        TrackedGaze fromFull(full, params), fromPruned(pruned, params);
        size_t next = 0;
        int differing = 0;
        for (double t = 0.0; t < 4.0; t += 0.011) {
            for (; next < samples.size() && samples[next].timeSeconds <= t; ++next) {
                full.Add(samples[next]);
                pruned.Add(samples[next]);
            }
            pruned.DropBefore(t - TrackerLookbackSeconds(params));
            differing += test::SameGazeBits(fromFull.At(t), fromPruned.At(t)) ? 0 : 1;
        }
        CHECK(differing == 0);
        CHECK(pruned.Size() < full.Size() / 2);  // it did prune
    }
}
