// RunConfig to and from TOML text and JSON (run manifests record ConfigToJson). Loaders validate
// like ResolveConfig; `origin` names the source in error messages.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "config/config.h"

namespace fovrt {

RunConfig LoadConfigFile(const std::string& path);                       // file + validation
RunConfig ConfigFromTomlString(const std::string& text, const std::string& origin = "<string>");
RunConfig ConfigFromJson(const nlohmann::json& json);                     // e.g. a run manifest

// Every key with its value, defaults included; the same keys and order in both forms.
std::string ConfigToToml(const RunConfig& config);
nlohmann::json ConfigToJson(const RunConfig& config);

}  // namespace fovrt
