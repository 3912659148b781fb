// The gaze sources: Lissajous (thesis default), recorded CSV traces, static.
#pragma once

#include <filesystem>
#include <istream>
#include <string>
#include <vector>

#include "gaze/gaze_source.h"

namespace fovrt {

class LissajousGaze final : public GazeSource {
public:
    LissajousGaze(const GazeParams& params, const Fov& referenceFov);
    std::string Name() const override { return "lissajous"; }
    GazeSample At(double timeSeconds) const override;
    // The curve value at t: a pixel on the reference image (units "px") or (yaw, pitch) degrees.
    vec2 CurveAt(double timeSeconds) const;

private:
    GazeParams params_;
    EyeCamera reference_;
};

class StaticGaze final : public GazeSource {
public:
    StaticGaze(float yawDeg, float pitchDeg) : direction_(GazeDirectionFromAngles(yawDeg, pitchDeg)) {}
    std::string Name() const override { return "static"; }
    GazeSample At(double timeSeconds) const override { return GazeSample{timeSeconds, direction_, true}; }

private:
    vec3 direction_;
};

struct GazeTraceSample {
    double timeMs = 0.0;
    float yawDeg = 0.0f;
    float pitchDeg = 0.0f;
    bool valid = true;  // false: NaN / empty angles (blink, tracker loss)
};

// Parses a gaze CSV. `name` is used in error messages ("name:line: ..."). Rules: '#' lines and
// blank lines are skipped; the first other line is the header (comma-separated, names trimmed,
// case-insensitive, a UTF-8 byte-order mark before it skipped) and must contain n (or time_ms),
// x and y, each once; extra columns are ignored. Each
// data row needs finite, non-decreasing n; x/y empty or NaN marks an invalid sample, otherwise
// they must be finite with |angle| < 90. At least one valid sample is required.
std::vector<GazeTraceSample> ParseGazeTraceCsv(std::istream& in, const std::string& name);
std::vector<GazeTraceSample> LoadGazeTraceCsv(const std::filesystem::path& path);

class TraceGaze final : public GazeSource {
public:
    // Samples must be as ParseGazeTraceCsv returns them (non-empty, sorted, one valid). Time t
    // plays the trace at its first row + startMs + t·1000; `loop`: past the last row, from the
    // first row again.
    TraceGaze(std::vector<GazeTraceSample> samples, double startMs = 0.0, bool loop = false);
    std::string Name() const override { return "trace"; }
    // Linear interpolation of the angles between the bracketing samples; clamped to the first /
    // last sample outside the trace. If a bracketing sample is invalid the result is invalid and
    // carries the direction of the nearest valid sample at or before it (else after it).
    GazeSample At(double timeSeconds) const override;
    double EndSeconds() const override;
    double DurationMs() const { return samples_.back().timeMs - samples_.front().timeMs; }
    const std::vector<GazeTraceSample>& samples() const { return samples_; }

private:
    std::vector<GazeTraceSample> samples_;
    std::vector<int> lastValid_;  // index of the last valid sample at or before i, -1 if none
    int firstValid_ = 0;
    double startMs_ = 0.0;
    bool loop_ = false;
};

}  // namespace fovrt
