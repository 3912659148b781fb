// GazeSource: where the eye looks, over time. A gaze sample is a unit direction in head space
// (-Z forward, +Y up) with a timestamp; each eye turns it into its own pixel position through its
// EyeCamera (foveation/, metrics regions).
#pragma once

#include <memory>
#include <string>

#include "core/math.h"

namespace fovrt {

struct GazeSample {
    double timeSeconds = 0.0;
    vec3 direction = vec3(0, 0, -1);  // head space, unit
    bool valid = true;                // false during blinks / tracker loss
};

class GazeSource {
public:
    virtual ~GazeSource() = default;
    virtual std::string Name() const = 0;
    virtual GazeSample At(double timeSeconds) const = 0;
};

}  // namespace fovrt
