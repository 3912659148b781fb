// GazeSource: where the eye looks, over time. A gaze sample is a unit direction in head space
// (-Z forward, +Y up) with a timestamp; each eye turns it into its own pixel position through its
// EyeCamera (foveation/, metrics regions).
#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "core/camera.h"
#include "core/math.h"
#include "core/setting_table.h"

namespace fovrt {

struct GazeSample {
    double timeSeconds = 0.0;
    vec3 direction = vec3(0, 0, -1);  // head space, unit
    bool valid = true;                // false during blinks / tracker loss
};

class GazeSource {
public:
    virtual ~GazeSource() = default;
    virtual std::string Name() const = 0;
    virtual GazeSample At(double timeSeconds) const = 0;
    // The last time (s) with gaze of its own; At() later repeats the sample there. Infinite for
    // sources without an end (Lissajous, static, a looped trace).
    virtual double EndSeconds() const { return std::numeric_limits<double>::infinity(); }
};

// Gaze angles <-> head-space direction (Fick convention, as eye trackers report): yaw about the
// head's up axis (+ = right), then pitch about the rotated horizontal axis (+ = up), in degrees.
// (0, 0) is straight ahead, -Z.
vec3 GazeDirectionFromAngles(float yawDeg, float pitchDeg);
vec2 GazeAnglesFromDirection(const vec3& direction);  // (yaw, pitch) in degrees

// Head-space gaze -> this eye's space. StereoRig eyes share the head's orientation (parallel
// axes; vergence ignored, i.e. gaze converges at infinity), so this is the identity today; use
// it so a future toed-in rig only changes here.
vec3 GazeInEye(const EyeCamera& eye, const vec3& gazeHead);
// Continuous pixel of the gaze on an eye's image (may lie outside the image). A direction at or
// behind the eye plane is pushed just in front of it.
vec2 GazePixel(const EyeCamera& eye, const vec3& gazeHead);

// The eye tracker between the true gaze and the renderer (gaze/tracker.h). Defaults: an ideal
// tracker, the renderer sees the true gaze at the frame's time.
struct TrackerParams {
    double rateHz = 0.0;     // samples per second; 0 = ideal: sampled at every frame's time
    double phaseMs = 0.0;    // time of sample 0 (rate > 0)
    double latencyMs = 0.0;  // eye-to-render delay: a sample is first used latencyMs after capture
    float noiseDeg = 0.0f;   // RMS angular error of a sample (isotropic Gaussian), seeded
    vec2 biasDeg = vec2(0.0f);  // constant (yaw, pitch) offset
    double dropout = 0.0;    // probability that a sample is lost (the true gaze's invalid samples always are)
    double blinkMs = 0.0;    // an invalid run this long is reported as a blink; shorter runs hold (rate > 0)
    uint32_t seed = 1;       // noise and dropouts
    std::string prediction = "none";  // one of PredictionNames(): none, cv (constant velocity), landing
    float saccadeDegPerS = 100.0f;    // saccade onset: angular speed between samples above this
};

// Parameters of every source, as loaded from the [gaze] config table (defaults = thesis).
struct GazeParams {
    std::string source = "lissajous";  // one of GazeSourceNames() (mouse: live windows only)

    // lissajous: p(t) = centre + offset + amplitude ⊙ sin(2π t frequency + phase).
    // units = "px": positions on a referenceWidth × referenceHeight image with the eye's FOV,
    // centre = image centre (thesis: amplitude (640, 360) on 1280×720, frequency (0.4, 0.5) Hz,
    // phase (90°, 0)); pixels become a head-space direction through that reference camera.
    // units = "deg": p is (yaw, pitch) in degrees (pitch up), centre = straight ahead.
    std::string units = "px";
    vec2 amplitude = vec2(640.0f, 360.0f);
    vec2 frequencyHz = vec2(0.4f, 0.5f);
    vec2 phaseDeg = vec2(90.0f, 0.0f);
    vec2 offset = vec2(0.0f);
    int referenceWidth = 1280;
    int referenceHeight = 720;

    // trace: CSV with a header row naming columns n (time, ms), x (yaw, deg), y (pitch, deg);
    // sample time = first row's time + startMs + t·1000.
    // recording: a headset recording (gaze/recording.h: time in s, dir_x/y/z head-frame unit
    // vectors); played like a trace, from its first row + traceStartMs.
    // traceStartMs must lie within the file. A run longer than the file from there is refused
    // unless traceEnd (one of TraceEndNames()) is "hold" (the last row's gaze, the frames marked)
    // or "loop" (from the first row again).
    std::string tracePath;
    std::string recordingPath;
    double traceStartMs = 0.0;
    std::string traceEnd = "refuse";

    // static: fixed angles.
    float yawDeg = 0.0f;
    float pitchDeg = 0.0f;

    // A blink (an invalid sample: a trace's NaN rows, tracker loss): "hold" foveates on the last
    // valid direction; "uniform" renders the frame with a uniform spp map at the foveated map's
    // mean (the same rays, spread evenly), since a closed eye has no fovea. The gaze pixel the
    // metrics use stays the held direction either way.
    std::string blink = "hold";

    TrackerParams tracker;
};

// The names gaze.source, gaze.units, gaze.trace_end, gaze.blink and gaze.prediction take
// (gaze_params.cpp).
NameList GazeSourceNames();
NameList GazeUnitNames();
NameList TraceEndNames();
NameList BlinkModeNames();
NameList PredictionNames();
// [gaze]: key, member, range, meaning of every GazeParams member, and of its TrackerParams
// (gaze.tracker_*, gaze.prediction, gaze.saccade_deg_s), in gaze_params.cpp.
std::span<const SettingRow<GazeParams>> GazeParamTable();
std::span<const SettingRow<TrackerParams>> TrackerParamTable();
// The rules between keys (a trace needs its path, degrees stay below 90, the tracker's blink and
// prediction need a rate), for readers that add their own context.
std::optional<ParamProblem> GazeParamConflict(const GazeParams& params);
// Throws fovrt::Error naming the first bad gaze.* key (with its range).
void ValidateGazeParams(const GazeParams& params);
// `referenceFov` is the FOV of the reference camera used by pixel-unit Lissajous gaze (the
// left eye's FOV, or the symmetric run FOV). Trace files are loaded here (errors name file:line).
std::unique_ptr<GazeSource> CreateGazeSource(const GazeParams& params, const Fov& referenceFov);

}  // namespace fovrt
