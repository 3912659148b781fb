#include "gaze/csv_fields.h"

#include <cctype>
#include <charconv>

#include "core/error.h"

namespace fovrt::csv {

std::string_view Trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

std::vector<std::string_view> Split(std::string_view line) {
    std::vector<std::string_view> fields;
    size_t start = 0;
    while (true) {
        size_t comma = line.find(',', start);
        fields.push_back(Trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    return fields;
}

std::string Lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

bool IsNanToken(std::string_view s) {
    std::string l = Lower(s);
    return l.empty() || l == "nan" || l == "-nan" || l == "+nan";
}

bool ParseDouble(std::string_view s, double& value) {
    if (s.empty()) return false;
    if (s.front() == '+') s.remove_prefix(1);
    auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    return ec == std::errc() && ptr == s.data() + s.size();
}

std::string_view SkipByteOrderMark(std::string_view line) {
    constexpr std::string_view kBom = "\xEF\xBB\xBF";
    if (line.substr(0, kBom.size()) == kBom) line.remove_prefix(kBom.size());
    return line;
}

std::vector<int> HeaderColumns(const std::vector<std::string_view>& header, std::span<const char* const> wanted,
                               const std::string& file, int line) {
    std::vector<int> columns(wanted.size(), -1);
    for (size_t i = 0; i < header.size(); ++i) {
        const std::string field = Lower(header[i]);
        for (size_t w = 0; w < wanted.size(); ++w) {
            if (field != wanted[w]) continue;
            if (columns[w] >= 0)
                Fail("{}:{}: column '{}' appears twice (fields {} and {})", file, line, wanted[w], columns[w] + 1,
                     i + 1);
            columns[w] = int(i);
        }
    }
    return columns;
}

}  // namespace fovrt::csv
