#include "gaze/sources.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>

#include "core/check.h"
#include "core/error.h"
#include "gaze/csv_fields.h"
#include "gaze/recording.h"
#include "gaze/tracker.h"

namespace fovrt {

vec3 GazeDirectionFromAngles(float yawDeg, float pitchDeg) {
    float yaw = Radians(yawDeg), pitch = Radians(pitchDeg);
    return vec3(std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch));
}

vec2 GazeAnglesFromDirection(const vec3& direction) {
    vec3 d = glm::normalize(direction);
    return vec2(Degrees(std::atan2(d.x, -d.z)), Degrees(std::asin(std::clamp(d.y, -1.0f, 1.0f))));
}

vec3 GazeInEye(const EyeCamera&, const vec3& gazeHead) { return gazeHead; }

vec2 GazePixel(const EyeCamera& eye, const vec3& gazeHead) {
    vec3 d = GazeInEye(eye, gazeHead);
    d.z = std::min(d.z, -1e-6f);
    return eye.PixelOfEyeDirection(d);
}

// ---- Lissajous -----------------------------------------------------------------------------

LissajousGaze::LissajousGaze(const GazeParams& params, const Fov& referenceFov)
    : params_(params),
      reference_(Pose(), referenceFov, std::max(params.referenceWidth, 1), std::max(params.referenceHeight, 1)) {}

vec2 LissajousGaze::CurveAt(double t) const {
    const bool pixels = params_.units == "px";
    vec2 centre = pixels ? 0.5f * vec2(float(params_.referenceWidth), float(params_.referenceHeight)) : vec2(0.0f);
    vec2 p;
    for (int i = 0; i < 2; ++i) {
        double arg = 2.0 * double(kPi) * t * double(params_.frequencyHz[i]) + double(Radians(params_.phaseDeg[i]));
        p[i] = centre[i] + params_.offset[i] + params_.amplitude[i] * float(std::sin(arg));
    }
    return p;
}

GazeSample LissajousGaze::At(double t) const {
    vec2 c = CurveAt(t);
    vec3 direction = params_.units == "px" ? reference_.EyeDirection(c) : GazeDirectionFromAngles(c.x, c.y);
    return GazeSample{t, direction, true};
}

// ---- Trace -----------------------------------------------------------------------------------

using csv::IsNanToken;
using csv::ParseDouble;
using csv::Trim;

std::vector<GazeTraceSample> ParseGazeTraceCsv(std::istream& in, const std::string& name) {
    std::vector<GazeTraceSample> samples;
    std::string line;
    int lineNumber = 0;
    int columnTime = -1, columnX = -1, columnY = -1;
    bool haveHeader = false;
    bool anyValid = false;
    while (std::getline(in, line)) {
        ++lineNumber;
        std::string_view view = Trim(haveHeader ? line : csv::SkipByteOrderMark(line));
        if (view.empty() || view.front() == '#') continue;
        std::vector<std::string_view> fields = csv::Split(view);
        if (!haveHeader) {
            static constexpr std::array<const char*, 4> kNames = {"n", "time_ms", "x", "y"};
            const std::vector<int> found = csv::HeaderColumns(fields, kNames, name, lineNumber);
            if (found[0] >= 0 && found[1] >= 0)
                Fail("{}:{}: gaze trace header names both n and time_ms (fields {} and {}); keep one time column",
                     name, lineNumber, found[0] + 1, found[1] + 1);
            columnTime = std::max(found[0], found[1]);
            columnX = found[2];
            columnY = found[3];
            if (columnTime < 0 || columnX < 0 || columnY < 0)
                Fail("{}:{}: gaze trace header must name columns n (time in ms), x and y (degrees); got '{}'",
                     name, lineNumber, std::string(view.substr(0, 80)));
            haveHeader = true;
            continue;
        }
        int needed = std::max({columnTime, columnX, columnY}) + 1;
        if (int(fields.size()) < needed)
            Fail("{}:{}: expected at least {} comma-separated fields, got {}", name, lineNumber, needed, fields.size());
        GazeTraceSample s;
        if (!ParseDouble(fields[size_t(columnTime)], s.timeMs) || !std::isfinite(s.timeMs))
            Fail("{}:{}: time '{}' is not a finite number", name, lineNumber,
                 std::string(fields[size_t(columnTime)].substr(0, 40)));
        if (!samples.empty() && s.timeMs < samples.back().timeMs)
            Fail("{}:{}: time {} ms goes backwards (previous row {} ms)", name, lineNumber, s.timeMs,
                 samples.back().timeMs);
        std::string_view fx = fields[size_t(columnX)], fy = fields[size_t(columnY)];
        if (IsNanToken(fx) || IsNanToken(fy)) {
            s.valid = false;
        } else {
            double x, y;
            if (!ParseDouble(fx, x) || !ParseDouble(fy, y))
                Fail("{}:{}: gaze angles '{}', '{}' are not numbers", name, lineNumber,
                     std::string(fx.substr(0, 40)), std::string(fy.substr(0, 40)));
            if (std::isnan(x) || std::isnan(y)) {
                s.valid = false;
            } else {
                if (!(std::abs(x) < 90.0) || !(std::abs(y) < 90.0))
                    Fail("{}:{}: gaze angles ({}, {}) out of range (|angle| < 90 degrees)", name, lineNumber, x, y);
                s.yawDeg = float(x);
                s.pitchDeg = float(y);
            }
        }
        anyValid = anyValid || s.valid;
        samples.push_back(s);
    }
    if (!haveHeader) Fail("{}: empty gaze trace (no header row)", name);
    if (samples.empty()) Fail("{}: gaze trace has a header but no samples", name);
    if (!anyValid) Fail("{}: gaze trace has no valid sample (all x/y are NaN or empty)", name);
    return samples;
}

std::vector<GazeTraceSample> LoadGazeTraceCsv(const std::filesystem::path& path) {
    // An ifstream opens a directory and reads nothing, which would read as an empty trace.
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) Fail("{}: is a directory, not a gaze trace (CSV)", path.string());
    std::ifstream in(path);
    if (!in) Fail("cannot open gaze trace '{}'", path.string());
    return ParseGazeTraceCsv(in, path.string());
}

TraceGaze::TraceGaze(std::vector<GazeTraceSample> samples, double startMs, bool loop)
    : samples_(std::move(samples)), startMs_(startMs), loop_(loop) {
    FOVRT_CHECK(!samples_.empty());
    lastValid_.resize(samples_.size());
    int last = -1;
    firstValid_ = -1;
    for (size_t i = 0; i < samples_.size(); ++i) {
        if (samples_[i].valid) {
            last = int(i);
            if (firstValid_ < 0) firstValid_ = int(i);
        }
        lastValid_[i] = last;
    }
    FOVRT_CHECK(firstValid_ >= 0);
}

double TraceGaze::EndSeconds() const {
    if (loop_ && DurationMs() > 0.0) return std::numeric_limits<double>::infinity();
    return (DurationMs() - startMs_) / 1000.0;
}

GazeSample TraceGaze::At(double timeSeconds) const {
    double fromFirstMs = startMs_ + timeSeconds * 1000.0;
    if (loop_ && DurationMs() > 0.0 && fromFirstMs > DurationMs()) fromFirstMs = std::fmod(fromFirstMs, DurationMs());
    const double ms = samples_.front().timeMs + fromFirstMs;
    auto direction = [&](const GazeTraceSample& s) { return GazeDirectionFromAngles(s.yawDeg, s.pitchDeg); };
    auto invalidAt = [&](size_t i) {
        int v = lastValid_[i] >= 0 ? lastValid_[i] : firstValid_;
        return GazeSample{timeSeconds, direction(samples_[size_t(v)]), false};
    };
    // First sample with time > ms; the bracket is [hi - 1, hi].
    auto it = std::upper_bound(samples_.begin(), samples_.end(), ms,
                               [](double t, const GazeTraceSample& s) { return t < s.timeMs; });
    if (it == samples_.begin() || it == samples_.end()) {  // clamp outside the trace
        size_t i = it == samples_.begin() ? 0 : samples_.size() - 1;
        if (!samples_[i].valid) return invalidAt(i);
        return GazeSample{timeSeconds, direction(samples_[i]), true};
    }
    size_t hi = size_t(it - samples_.begin()), lo = hi - 1;
    const GazeTraceSample& a = samples_[lo];
    const GazeTraceSample& b = samples_[hi];
    if (!a.valid || !b.valid) return invalidAt(lo);
    double span = b.timeMs - a.timeMs;
    float t = span > 0.0 ? float((ms - a.timeMs) / span) : 0.0f;
    return GazeSample{timeSeconds,
                      GazeDirectionFromAngles(a.yawDeg + t * (b.yawDeg - a.yawDeg),
                                              a.pitchDeg + t * (b.pitchDeg - a.pitchDeg)),
                      true};
}

// ---- Factory ---------------------------------------------------------------------------------

std::unique_ptr<GazeSource> CreateGazeSource(const GazeParams& params, const Fov& referenceFov) {
    ValidateGazeParams(params);
    if (params.source == "mouse")
        Fail("gaze.source = 'mouse' needs a window: use `fovrt preview` (headless runs take lissajous, "
             "trace, recording or static, or replay a recorded session with --replay)");
    if (params.source == "lissajous") return std::make_unique<LissajousGaze>(params, referenceFov);
    if (params.source == "static") return std::make_unique<StaticGaze>(params.yawDeg, params.pitchDeg);
    const bool recording = params.source == "recording";
    auto trace = std::make_unique<TraceGaze>(
        recording ? LoadGazeRecordingCsv(params.recordingPath) : LoadGazeTraceCsv(params.tracePath),
        params.traceStartMs, params.traceEnd == "loop");
    // Outside the file every frame would freeze on its first or last row.
    if (!(params.traceStartMs >= 0.0 && params.traceStartMs <= trace->DurationMs()))
        Fail("gaze.trace_start_ms: {} ms is outside {} '{}', which lasts {:.6g} ms from its first row",
             params.traceStartMs, recording ? "gaze.recording_path" : "gaze.trace_path",
             recording ? params.recordingPath : params.tracePath, trace->DurationMs());
    return trace;
}

}  // namespace fovrt
