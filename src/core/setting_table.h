// Settings tables: one row per config key, saying its key, the struct member it sets, the values
// it allows and what it means (the default is the member's initialiser). The config reader and
// writer, the modules' checks, `fovrt config --keys` and the preview panel's sliders all walk
// the rows, so a setting is added in two places: its member and its row. The tables:
// denoise/params.cpp, foveation/foveation_params.cpp, gaze/gaze_params.cpp,
// src/config/settings_tables.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <fmt/format.h>

#include "core/check.h"
#include "core/math.h"

namespace fovrt {

// Allowed values of a number; an open end excludes its bound. An infinite bound means "any finite
// value" on that side.
struct ParamRange {
    double min = 0.0;
    double max = 0.0;
    bool minOpen = false;
    bool maxOpen = false;

    bool Contains(double value) const;  // false for NaN and infinities
    std::string Describe() const;       // "(0, 1]"
    constexpr bool Empty() const { return min == 0.0 && max == 0.0 && !minOpen && !maxOpen; }
};

constexpr ParamRange Closed(double min, double max) { return {min, max, false, false}; }
constexpr ParamRange OpenMin(double min, double max) { return {min, max, true, false}; }
constexpr ParamRange OpenMax(double min, double max) { return {min, max, false, true}; }
constexpr ParamRange Open(double min, double max) { return {min, max, true, true}; }

// The names a string setting takes (foveation models, gaze sources, ...), each listed once by the
// module that acts on them.
using NameList = std::span<const char* const>;

// What a row says about its setting, whatever struct holds it.
struct ParamInfo {
    const char* key = nullptr;      // full TOML key: "denoise.svgf.alpha_color"
    ParamRange range = {};          // numbers (each element of an array); unused for bools and strings
    const char* doc = nullptr;      // one line
    NameList (*names)() = nullptr;  // strings: the values allowed; nullptr = any
    bool nonEmpty = false;          // strings: must not be empty
    ParamRange slider = {};         // the preview panel's slider span (inside `range`); empty = none
    // strings: the path of a file the run reads. Written relative in a config file it is taken
    // from that file's folder, given relative to --set from the working directory; the reader
    // stores it absolute (config.cpp).
    bool path = false;
    // path strings that may also be a name (scene.name: a built-in scene): a bare word, without
    // '/' or '.', is a name and stays as written (every loadable file has an extension).
    bool orName = false;
};

// A value that breaks a rule: the key to blame and why ("9 is out of range [0, 8]").
struct ParamProblem {
    std::string key;
    std::string message;
};

using FovDegrees = std::optional<std::array<float, 4>>;  // camera.fov_deg: absent or 4 angles

// One row of a struct's table: the info and the member it describes. uint64_t members are byte
// sizes (memory_budget: also "512MiB").
template <class Struct>
struct SettingRow {
    ParamInfo info;
    std::variant<bool Struct::*, int Struct::*, uint32_t Struct::*, int64_t Struct::*, uint64_t Struct::*,
                 float Struct::*, double Struct::*, vec2 Struct::*, FovDegrees Struct::*, std::string Struct::*,
                 std::vector<std::string> Struct::*>
        member;
};

// Calls visit(info, value) for every row of `table`; `value` is the member inside `section`
// (const when `section` is).
template <class Section, class Table, class Visit>
void VisitRows(Section& section, const Table& table, Visit&& visit) {
    for (const auto& row : table)
        std::visit([&](auto member) { visit(row.info, section.*member); }, row.member);
}

// What is wrong with `value` for its row ("9 is out of range [0, 8]", "'x' is not one of a, b
// (did you mean 'a'?)", "must not be empty"), or nullopt.
template <class Number>
    requires std::is_arithmetic_v<Number>
std::optional<std::string> SettingValueProblem(const ParamInfo& info, Number value) {
    if (info.range.Contains(double(value))) return std::nullopt;
    return fmt::format("{} is out of range {}", value, info.range.Describe());
}
std::optional<std::string> SettingValueProblem(const ParamInfo& info, const std::string& value);
std::optional<std::string> SettingValueProblem(const ParamInfo& info, const vec2& value);
std::optional<std::string> SettingValueProblem(const ParamInfo& info, const FovDegrees& value);
inline std::optional<std::string> SettingValueProblem(const ParamInfo&, bool) { return std::nullopt; }
inline std::optional<std::string> SettingValueProblem(const ParamInfo&, const std::vector<std::string>&) {
    return std::nullopt;  // lists are checked by their module (denoise.denoisers: denoise/variants.h)
}

// fovrt::Error "<key>: <problem>" for the first row whose value in `section` is bad.
void FailSettingProblem(const ParamInfo& info, const std::string& problem);
template <class Section, class Table>
void ValidateRows(const Section& section, const Table& table) {
    VisitRows(section, table, [](const ParamInfo& info, const auto& value) {
        if (std::optional<std::string> problem = SettingValueProblem(info, value))
            FailSettingProblem(info, *problem);
    });
}

// The row of `table` whose key is `key`; nullptr when none is.
template <class Table>
const ParamInfo* FindRow(const Table& table, const std::string& key) {
    for (const auto& row : table)
        if (key == row.info.key) return &row.info;
    return nullptr;
}

// The preview panel's slider span of `key`, so a slider never offers a value the checks refuse.
template <class Table>
ParamRange SliderSpan(const Table& table, const std::string& key) {
    const ParamInfo* row = FindRow(table, key);
    FOVRT_CHECK(row != nullptr && !row->slider.Empty());
    return row->slider;
}

// What is wrong with a table row (no key, no doc, min > max, an empty open range, a slider outside
// the range), or nullptr. The tables static_assert it over every row; tests feed it bad rows.
constexpr const char* ParamRowProblem(const ParamInfo& info) {
    if (info.key == nullptr || info.key[0] == '\0') return "row without a key";
    if (info.doc == nullptr || info.doc[0] == '\0') return "row without a doc line";
    if (info.range.min > info.range.max) return "range with min > max";
    if (info.range.min == info.range.max && (info.range.minOpen || info.range.maxOpen))
        return "open range with min == max (empty)";
    if (!info.slider.Empty() && (info.slider.min < info.range.min || info.slider.max > info.range.max ||
                                 (info.range.minOpen && info.slider.min == info.range.min) ||
                                 (info.range.maxOpen && info.slider.max == info.range.max)))
        return "slider span outside the range";
    return nullptr;
}

template <class Table>
constexpr bool RowsWellFormed(const Table& rows) {
    for (const auto& row : rows)
        if (ParamRowProblem(row.info) != nullptr) return false;
    return true;
}

}  // namespace fovrt
