// The one validity rule for material colours, shared by the MTL reader (obj_loader.cpp) and the
// scene file's [[material]] overrides (scene_file.cpp), so that a value one refuses the other
// refuses too.
#include <cmath>

#include <fmt/format.h>

#include "scene/loaders.h"

namespace fovrt::detail {

std::string MaterialColourProblem(const std::vector<double>& components) {
    for (double v : components) {
        if (!std::isfinite(v)) return fmt::format("{} is not a finite number", v);
        if (v < 0.0) return fmt::format("{} must be >= 0", v);
        if (v > kMaxMaterialColour)
            return fmt::format("{} is above {:g} (its square would overflow 32-bit float)", v, kMaxMaterialColour);
    }
    return "";
}

}  // namespace fovrt::detail
