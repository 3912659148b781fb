// Headset gaze recordings: one row per sample with `time` (seconds) and the gaze direction as a
// unit vector in the headset's frame (`dir_x, dir_y, dir_z`, +z ahead, +x right, +y up: Unity's
// left-handed head frame, as the Vive Pro Eye's SRanipal Unity API and the recordings in
// ../shared/gaze/ give it), optionally the gaze origin (`ori_x, ori_y, ori_z`, metres). Rows are
// converted to the angle traces TraceGaze plays (yaw + = right, pitch + = up, degrees), so a
// recording behaves exactly as a trace: interpolated, clamped at the ends, invalid rows = blinks.
#pragma once

#include <filesystem>
#include <istream>
#include <string>
#include <vector>

#include "gaze/sources.h"

namespace fovrt {

// Headset frame (+z ahead, left-handed) -> fovrt head space (-Z ahead, right-handed): z flips,
// x (right) and y (up) keep their signs.
vec3 HeadDirectionFromHeadset(const vec3& headsetDirection);

// Parses a recording. `name` is used in error messages ("name:line: ..."). Rules: the first
// non-blank line is the header (a UTF-8 byte-order mark before it is skipped); columns are found
// by name (case-insensitive, any order, extra columns ignored, a known name given twice refused):
// time, dir_x, dir_y, dir_z required, ori_x, ori_y, ori_z optional. Times are
// finite seconds, non-decreasing, and become milliseconds from the first row. A row is invalid
// (blink, tracking loss) when its direction is empty / NaN, or exactly (0, 0, 1) with the
// origin exactly (0, 0, 0) (or no origin columns) — the Vive's "no sample" row. Other
// directions must be finite, of length 1 ± 0.01, and ahead of the eye (|yaw|, |pitch| < 90°).
// At least one valid row is required.
std::vector<GazeTraceSample> ParseGazeRecordingCsv(std::istream& in, const std::string& name);
std::vector<GazeTraceSample> LoadGazeRecordingCsv(const std::filesystem::path& path);

}  // namespace fovrt
