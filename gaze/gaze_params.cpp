// [gaze]: one row per key of GazeParams and of its TrackerParams (defaults: their initialisers,
// gaze/gaze_source.h), the names each string key takes, and the rules between keys. The config
// reader, ValidateGazeParams / ValidateTrackerParams, `fovrt config --keys` and the preview
// panel's sliders read these rows.
#include <array>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "gaze/gaze_source.h"
#include "gaze/tracker.h"

namespace fovrt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr ParamRange kFinite = Open(-kInf, kInf);
constexpr ParamRange kSeed = Closed(0, double(std::numeric_limits<uint32_t>::max()));
// Angles of a direction in front of the eye (Fick yaw and pitch).
constexpr ParamRange kAheadDeg = Open(-90, 90);
constexpr ParamRange kAheadSlider = Closed(-60, 60);

constexpr std::array<const char*, 5> kSources = {"lissajous", "trace", "recording", "static", "mouse"};
constexpr std::array<const char*, 2> kUnits = {"px", "deg"};
constexpr std::array<const char*, 3> kTraceEnds = {"refuse", "hold", "loop"};
constexpr std::array<const char*, 2> kBlinkModes = {"hold", "uniform"};
constexpr std::array<const char*, 3> kPredictions = {"none", "cv", "landing"};

using G = GazeParams;
constexpr std::array<SettingRow<GazeParams>, 15> kGazeRows{{
    {{.key = "gaze.source", .doc = "where the eye looks (mouse: live windows only)", .names = GazeSourceNames},
     &G::source},
    {{.key = "gaze.units", .doc = "lissajous: px on a reference_width × reference_height image, or deg (yaw, pitch)",
      .names = GazeUnitNames},
     &G::units},
    {{.key = "gaze.amplitude", .range = kFinite, .doc = "lissajous: amplitude (x, y) in units",
      .slider = Closed(0, 1280)},
     &G::amplitude},
    {{.key = "gaze.frequency_hz", .range = Closed(0, kInf), .doc = "lissajous: frequency (x, y) in Hz",
      .slider = Closed(0, 2)},
     &G::frequencyHz},
    {{.key = "gaze.phase_deg", .range = kFinite, .doc = "lissajous: phase (x, y) in degrees"}, &G::phaseDeg},
    {{.key = "gaze.offset", .range = kFinite, .doc = "lissajous: centre offset (x, y) in units"}, &G::offset},
    {{.key = "gaze.reference_width", .range = Closed(1, 16384), .doc = "lissajous px: reference image width"},
     &G::referenceWidth},
    {{.key = "gaze.reference_height", .range = Closed(1, 16384), .doc = "lissajous px: reference image height"},
     &G::referenceHeight},
    {{.key = "gaze.trace_path", .doc = "trace: CSV with columns n (ms), x, y (degrees)", .path = true},
     &G::tracePath},
    {{.key = "gaze.trace_start_ms", .range = kFinite, .doc = "trace, recording: start offset after the first row"},
     &G::traceStartMs},
    {{.key = "gaze.trace_end",
      .doc = "trace, recording: a run longer than the file from trace_start_ms is refused, holds the last row "
             "(frames marked gaze_held) or loops",
      .names = TraceEndNames},
     &G::traceEnd},
    {{.key = "gaze.yaw_deg", .range = kAheadDeg, .doc = "static: yaw (+ = right)", .slider = kAheadSlider},
     &G::yawDeg},
    {{.key = "gaze.pitch_deg", .range = kAheadDeg, .doc = "static: pitch (+ = up)", .slider = kAheadSlider},
     &G::pitchDeg},
    {{.key = "gaze.recording_path", .doc = "recording: headset recording CSV (gaze/recording.h)", .path = true},
     &G::recordingPath},
    {{.key = "gaze.blink", .doc = "an invalid sample: hold the last direction, or a uniform map at the mean spp",
      .names = BlinkModeNames},
     &G::blink},
}};

using T = TrackerParams;
constexpr std::array<SettingRow<TrackerParams>, 10> kTrackerRows{{
    {{.key = "gaze.tracker_rate_hz", .range = Closed(0, 10000),
      .doc = "eye tracker samples per second; 0 = ideal, sampled at every frame", .slider = Closed(0, 1000)},
     &T::rateHz},
    {{.key = "gaze.tracker_phase_ms", .range = Closed(-1000, 1000), .doc = "time of tracker sample 0"},
     &T::phaseMs},
    {{.key = "gaze.tracker_latency_ms", .range = Closed(0, 10000), .doc = "eye-to-render delay of a sample",
      .slider = Closed(0, 500)},
     &T::latencyMs},
    {{.key = "gaze.tracker_noise_deg", .range = Closed(0, 45), .doc = "RMS angular noise of a sample (seeded)",
      .slider = Closed(0, 10)},
     &T::noiseDeg},
    {{.key = "gaze.tracker_bias_deg", .range = Closed(-45, 45), .doc = "constant (yaw, pitch) offset"},
     &T::biasDeg},
    {{.key = "gaze.tracker_dropout", .range = OpenMax(0, 1), .doc = "probability that a sample is lost"},
     &T::dropout},
    {{.key = "gaze.tracker_blink_ms", .range = Closed(0, 10000),
      .doc = "an invalid run this long is a blink; shorter runs hold (needs tracker_rate_hz > 0)"},
     &T::blinkMs},
    {{.key = "gaze.tracker_seed", .range = kSeed, .doc = "seed of the tracker's noise and dropouts"}, &T::seed},
    {{.key = "gaze.prediction", .doc = "none, cv (constant velocity) or landing (saccade landing point)",
      .names = PredictionNames},
     &T::prediction},
    {{.key = "gaze.saccade_deg_s", .range = OpenMin(0, 2000), .doc = "saccade onset: speed between samples above this"},
     &T::saccadeDegPerS},
}};
static_assert(RowsWellFormed(kGazeRows) && RowsWellFormed(kTrackerRows),
              "a [gaze] row is malformed (see ParamRowProblem)");

std::optional<ParamProblem> TrackerParamConflict(const TrackerParams& p) {
    if (p.blinkMs > 0.0 && p.rateHz == 0.0)
        return ParamProblem{"gaze.tracker_blink_ms",
                            fmt::format("{} needs gaze.tracker_rate_hz > 0 (runs of samples)", p.blinkMs)};
    if (p.prediction != "none" && p.rateHz == 0.0)
        return ParamProblem{"gaze.prediction",
                            fmt::format("'{}' needs gaze.tracker_rate_hz > 0 (it extrapolates from the tracker's "
                                        "samples)",
                                        p.prediction)};
    return std::nullopt;
}

}  // namespace

NameList GazeSourceNames() { return kSources; }
NameList GazeUnitNames() { return kUnits; }
NameList TraceEndNames() { return kTraceEnds; }
NameList BlinkModeNames() { return kBlinkModes; }
NameList PredictionNames() { return kPredictions; }

std::span<const SettingRow<GazeParams>> GazeParamTable() { return kGazeRows; }
std::span<const SettingRow<TrackerParams>> TrackerParamTable() { return kTrackerRows; }

std::optional<ParamProblem> GazeParamConflict(const GazeParams& p) {
    if (p.units == "deg" && (std::abs(p.offset.x) + std::abs(p.amplitude.x) >= 90.0f ||
                             std::abs(p.offset.y) + std::abs(p.amplitude.y) >= 90.0f))
        return ParamProblem{"gaze.amplitude", "gaze.offset + gaze.amplitude must stay below 90 degrees"};
    if (p.source == "trace" && p.tracePath.empty())
        return ParamProblem{"gaze.trace_path", "must be set when gaze.source = \"trace\""};
    if (p.source == "recording" && p.recordingPath.empty())
        return ParamProblem{"gaze.recording_path", "must be set when gaze.source = \"recording\""};
    return TrackerParamConflict(p.tracker);
}

void ValidateTrackerParams(const TrackerParams& params) {
    ValidateRows(params, TrackerParamTable());
    if (std::optional<ParamProblem> problem = TrackerParamConflict(params))
        Fail("{}: {}", problem->key, problem->message);
}

void ValidateGazeParams(const GazeParams& params) {
    ValidateRows(params, GazeParamTable());
    ValidateRows(params.tracker, TrackerParamTable());
    if (std::optional<ParamProblem> problem = GazeParamConflict(params)) Fail("{}: {}", problem->key, problem->message);
}

}  // namespace fovrt
