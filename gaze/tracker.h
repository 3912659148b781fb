// The eye tracker between the eye and the renderer (SPEC §15): from the TRUE gaze over time
// (a GazeSource) to the gaze the renderer sees. The tracker captures the eye at its own rate and
// phase, adds a constant bias and seeded Gaussian noise, loses samples (a dropout probability,
// and always where the true gaze is invalid), reports a blink once an invalid run lasts
// blinkMs, and its samples reach the renderer latencyMs after capture. A predictor may then
// move the gaze to where the eye is expected to be: constant-velocity extrapolation over the
// sample's age, or the landing point of a saccade in flight (main-sequence fit, below).
//
// Everything is a pure function of the render time: sample k's noise and dropout are hashed from
// (seed, k), so any frame order and any number of queries give the same tracked gaze.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "gaze/gaze_source.h"

namespace fovrt {

// ---- Saccade model (main sequence, SPEC §15) ---------------------------------------------------

// V_peak = V_max (1 - e^{-A/C}), the exponential main sequence, V_max = 600°/s, C = 14°.
constexpr double kMainSequenceVmaxDegPerS = 600.0;
constexpr double kMainSequenceCDeg = 14.0;
double MainSequencePeakVelocity(double amplitudeDeg);
// A saccade's velocity is a raised cosine of duration D with peak V_peak(A): it covers
// A = V_peak D / 2, so D = 2 A / V_peak(A) (10° -> 65 ms, 20° -> 88 ms).
double SaccadeDurationS(double amplitudeDeg);
// Distance covered `elapsedS` after onset (0 before, A after the end).
double SaccadeDisplacementDeg(double amplitudeDeg, double elapsedS);

// The landing predictor. `anglesDeg` are consecutive valid tracker samples (yaw, pitch), oldest
// first, `periodS` apart. When the newest moved faster than `onsetDegPerS` since the previous
// one (a saccade in flight), takes as its start the last sample m slower than a fifth of that
// (before the acceleration), and fits the amplitude A and the onset's time (from 2 periods before
// sample m to 1 after) to the distances covered since m — least squares over the model above, a grid (A in
// 0.5° steps up to 90°) then pattern searches from its 8 best points — once three samples have followed m
// (two parameters: two samples fit too many saccades). Returns the start + A along the direction
// travelled; nullopt outside a saccade and before that third sample.
std::optional<vec2> PredictSaccadeLanding(const std::vector<vec2>& anglesDeg, double periodS,
                                          double onsetDegPerS);

// The angle between two directions in degrees, exact 0 for equal ones (atan2(|a×b|, a·b): acos
// of a float dot product cannot resolve angles below ~0.02°).
float AngleBetweenDeg(const vec3& a, const vec3& b);

// ---- Tracker sampling ----------------------------------------------------------------------

// Constant-velocity extrapolation: newest + (newest - previous) / periodS · horizonS.
vec2 ExtrapolateConstantVelocity(const vec2& previous, const vec2& newest, double periodS, double horizonS);
// Sample `key`'s noise: isotropic Gaussian in (yaw, pitch) with E|n|² = rmsDeg², σ = rms/√2 per axis.
vec2 TrackerNoiseDeg(uint32_t seed, uint64_t key, float rmsDeg);
// Whether sample `key` is lost, with `probability`.
bool TrackerDropout(uint32_t seed, uint64_t key, double probability);
// The newest sample whose capture time + latency is at or before t (rate > 0): floor((t − L − phase) · rate).
int64_t NewestSampleIndex(const TrackerParams& params, double timeSeconds);
double SampleCaptureTime(const TrackerParams& params, int64_t index);

// True when the tracker passes the true gaze through unchanged (the defaults).
bool IsIdealTracker(const TrackerParams& params);
// How far back TrackedGaze::At(t) reads the true gaze: never before t − this (a live history of
// true samples keeps this much: gaze/live_gaze_history.h).
double TrackerLookbackSeconds(const TrackerParams& params);
// Throws fovrt::Error naming the first bad gaze.tracker_* / gaze.prediction key.
void ValidateTrackerParams(const TrackerParams& params);

// One sample as the tracker reports it.
struct TrackerSample {
    double captureSeconds = 0.0;
    vec2 anglesDeg = vec2(0.0f);  // (yaw, pitch) with bias and noise
    bool valid = false;           // false: dropout or invalid true gaze
};

// The tracked gaze of a true gaze source, itself a GazeSource (At = what the renderer sees at t).
class TrackedGaze final : public GazeSource {
public:
    // `truth` must outlive this.
    TrackedGaze(const GazeSource& truth, const TrackerParams& params);
    std::string Name() const override { return truth_.Name(); }
    GazeSample At(double timeSeconds) const override;
    // Sample `index` (rate > 0).
    TrackerSample Sample(int64_t index) const;
    const TrackerParams& Params() const { return params_; }

private:
    TrackerSample Observe(double captureSeconds, uint64_t key) const;
    GazeSample Predict(double timeSeconds, int64_t newestValid) const;

    const GazeSource& truth_;
    TrackerParams params_;
};

}  // namespace fovrt
