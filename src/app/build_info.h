// Versions of fovrt and of the libraries it was built with, for `fovrt info` and run manifests.
#pragma once

#include <nlohmann/json.hpp>

namespace fovrt {

nlohmann::json BuildInfoJson();

}  // namespace fovrt
