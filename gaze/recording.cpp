#include "gaze/recording.h"

#include <array>
#include <cmath>
#include <fstream>

#include "core/error.h"
#include "gaze/csv_fields.h"

namespace fovrt {

vec3 HeadDirectionFromHeadset(const vec3& d) { return vec3(d.x, d.y, -d.z); }

namespace {

struct Columns {
    int time = -1;
    std::array<int, 3> dir{-1, -1, -1};
    std::array<int, 3> ori{-1, -1, -1};
    bool HasOrigin() const { return ori[0] >= 0 && ori[1] >= 0 && ori[2] >= 0; }
};

Columns FindColumns(const std::vector<std::string_view>& header, const std::string& name, int line) {
    static constexpr std::array<const char*, 7> kNames = {"time",  "dir_x", "dir_y", "dir_z",
                                                          "ori_x", "ori_y", "ori_z"};
    const std::vector<int> found = csv::HeaderColumns(header, kNames, name, line);
    Columns c;
    c.time = found[0];
    for (size_t a = 0; a < 3; ++a) {
        c.dir[a] = found[1 + a];
        c.ori[a] = found[4 + a];
    }
    return c;
}

}  // namespace

std::vector<GazeTraceSample> ParseGazeRecordingCsv(std::istream& in, const std::string& name) {
    std::vector<GazeTraceSample> samples;
    std::string line;
    int lineNumber = 0;
    Columns columns;
    bool haveHeader = false, anyValid = false;
    double firstTime = 0.0;
    while (std::getline(in, line)) {
        ++lineNumber;
        const std::string_view view = csv::Trim(haveHeader ? line : csv::SkipByteOrderMark(line));
        if (view.empty()) continue;
        const std::vector<std::string_view> fields = csv::Split(view);
        if (!haveHeader) {
            columns = FindColumns(fields, name, lineNumber);
            if (columns.time < 0 || columns.dir[0] < 0 || columns.dir[1] < 0 || columns.dir[2] < 0)
                Fail("{}:{}: gaze recording header must name columns time (s), dir_x, dir_y and dir_z; got '{}'",
                     name, lineNumber, std::string(view.substr(0, 80)));
            haveHeader = true;
            continue;
        }
        auto field = [&](int column) -> std::string_view {
            if (column >= int(fields.size()))
                Fail("{}:{}: expected at least {} comma-separated fields, got {}", name, lineNumber, column + 1,
                     fields.size());
            return fields[size_t(column)];
        };
        auto number = [&](int column, const char* what) {
            double value = 0.0;
            const std::string_view text = field(column);
            if (!csv::ParseDouble(text, value) || !std::isfinite(value))
                Fail("{}:{}: {} '{}' is not a finite number", name, lineNumber, what, std::string(text.substr(0, 40)));
            return value;
        };
        const double time = number(columns.time, "time");
        if (samples.empty()) firstTime = time;
        GazeTraceSample s;
        s.timeMs = (time - firstTime) * 1000.0;
        if (!samples.empty() && s.timeMs < samples.back().timeMs)
            Fail("{}:{}: time {} s goes backwards (previous row {} s)", name, lineNumber, time,
                 firstTime + samples.back().timeMs / 1000.0);
        const bool missing = csv::IsNanToken(field(columns.dir[0])) || csv::IsNanToken(field(columns.dir[1])) ||
                             csv::IsNanToken(field(columns.dir[2]));
        if (missing) {
            s.valid = false;
        } else {
            const vec3 dir(float(number(columns.dir[0], "dir_x")), float(number(columns.dir[1], "dir_y")),
                           float(number(columns.dir[2], "dir_z")));
            const bool noOrigin = !columns.HasOrigin() ||
                                  (number(columns.ori[0], "ori_x") == 0.0 && number(columns.ori[1], "ori_y") == 0.0 &&
                                   number(columns.ori[2], "ori_z") == 0.0);
            if (dir == vec3(0, 0, 1) && noOrigin) {
                s.valid = false;
            } else {
                const float length = glm::length(dir);
                if (!(std::abs(length - 1.0f) <= 0.01f))
                    Fail("{}:{}: gaze direction ({}, {}, {}) is not a unit vector (length {})", name, lineNumber,
                         dir.x, dir.y, dir.z, length);
                if (!(dir.z > 0.0f))
                    Fail("{}:{}: gaze direction ({}, {}, {}) does not point ahead (+z)", name, lineNumber, dir.x,
                         dir.y, dir.z);
                const vec2 angles = GazeAnglesFromDirection(HeadDirectionFromHeadset(dir));
                if (!(std::abs(angles.x) < 90.0f) || !(std::abs(angles.y) < 90.0f))
                    Fail("{}:{}: gaze angles ({}, {}) out of range (|angle| < 90 degrees)", name, lineNumber,
                         angles.x, angles.y);
                s.yawDeg = angles.x;
                s.pitchDeg = angles.y;
            }
        }
        anyValid = anyValid || s.valid;
        samples.push_back(s);
    }
    if (!haveHeader) Fail("{}: empty gaze recording (no header row)", name);
    if (samples.empty()) Fail("{}: gaze recording has a header but no samples", name);
    if (!anyValid) Fail("{}: gaze recording has no valid sample (every row is a blink or tracking loss)", name);
    return samples;
}

std::vector<GazeTraceSample> LoadGazeRecordingCsv(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) Fail("cannot open gaze recording '{}'", path.string());
    return ParseGazeRecordingCsv(in, path.string());
}

}  // namespace fovrt
