// SppModel: turns a gaze direction into a per-pixel samples-per-pixel map for one eye (SPEC §7).
// Eccentricity is the angle between a pixel's view ray and the eye's gaze ray.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/camera.h"
#include "core/image.h"

namespace fovrt {

inline constexpr int kMaxSpp = 16;

class SppModel {
public:
    virtual ~SppModel() = default;
    virtual std::string Name() const = 0;
    // Fills `spp` (resized to the camera's resolution) with values in [1, kMaxSpp].
    // `gazeEye` is the gaze direction in this eye's space (unit, -Z forward).
    virtual void Generate(const EyeCamera& camera, const vec3& gazeEye, uint32_t frameIndex,
                          Plane<uint16_t>& spp) const = 0;
};

}  // namespace fovrt
