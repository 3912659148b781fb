// The CSV field helpers both gaze file readers (angle traces, headset recordings) share.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace fovrt::csv {

std::string_view Trim(std::string_view s);                   // spaces, tabs, '\r'
std::vector<std::string_view> Split(std::string_view line);  // on ',', each field trimmed
std::string Lower(std::string_view s);
bool IsNanToken(std::string_view s);                         // empty, nan, -nan, +nan (any case)
// Parses the whole field as a double; false on garbage (trailing characters included).
bool ParseDouble(std::string_view s, double& value);

}  // namespace fovrt::csv
