#include "core/setting_table.h"

#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "core/nearest_name.h"

namespace fovrt {

bool ParamRange::Contains(double value) const {
    if (!std::isfinite(value)) return false;
    if (value < min || value > max) return false;
    return !(minOpen && value == min) && !(maxOpen && value == max);
}

std::string ParamRange::Describe() const {
    // An infinite bound is never reached (values are finite): shown open.
    return fmt::format("{}{}, {}{}", minOpen || std::isinf(min) ? "(" : "[", min, max,
                       maxOpen || std::isinf(max) ? ")" : "]");
}

std::optional<std::string> SettingValueProblem(const ParamInfo& info, const std::string& value) {
    if (info.nonEmpty && value.empty()) return "must not be empty";
    if (info.names == nullptr) return std::nullopt;
    std::string list;
    for (const char* name : info.names()) {
        if (value == name) return std::nullopt;
        if (!list.empty()) list += ", ";
        list += name;
    }
    return fmt::format("'{}' is not one of {} (did you mean '{}'?)", value, list, NearestName(value, info.names()));
}

std::optional<std::string> SettingValueProblem(const ParamInfo& info, const vec2& value) {
    for (int i = 0; i < 2; ++i)
        if (!info.range.Contains(value[i]))
            return fmt::format("{} is out of range {}", value[i], info.range.Describe());
    return std::nullopt;
}

std::optional<std::string> SettingValueProblem(const ParamInfo& info, const FovDegrees& value) {
    if (!value) return std::nullopt;
    for (float angle : *value)
        if (!info.range.Contains(angle)) return fmt::format("{} is out of range {}", angle, info.range.Describe());
    return std::nullopt;
}

void FailSettingProblem(const ParamInfo& info, const std::string& problem) { Fail("{}: {}", info.key, problem); }

}  // namespace fovrt
