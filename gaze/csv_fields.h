// The CSV field helpers both gaze file readers (angle traces, headset recordings) share.
#pragma once

#include <span>
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

// The line without a leading UTF-8 byte-order mark (spreadsheets save one before the header).
std::string_view SkipByteOrderMark(std::string_view line);
// The header field of each name in `wanted` (case-insensitive), -1 when absent. A wanted name
// given twice fails with "<file>:<line>: column 'x' appears twice (fields 2 and 5)": reading
// either one would be a guess.
std::vector<int> HeaderColumns(const std::vector<std::string_view>& header, std::span<const char* const> wanted,
                               const std::string& file, int line);

}  // namespace fovrt::csv
