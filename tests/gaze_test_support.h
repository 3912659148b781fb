// Gaze helpers shared by the tests of gaze samples (live history, live tracker, recordings).
#pragma once

#include <cstring>

#include "gaze/gaze_source.h"

namespace fovrt::test {

// Two gaze samples equal bit for bit: time, direction and validity.
inline bool SameGazeBits(const GazeSample& a, const GazeSample& b) {
    return std::memcmp(&a.timeSeconds, &b.timeSeconds, sizeof(double)) == 0 &&
           std::memcmp(&a.direction, &b.direction, sizeof(vec3)) == 0 && a.valid == b.valid;
}

}  // namespace fovrt::test
