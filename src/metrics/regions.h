// Image regions for foveated error reporting (SPEC §8): whole, fovea (gaze-centred disc),
// periphery (its complement) and eccentricity bands. Eccentricity is the angle between a pixel's
// view ray (EyeCamera::EyeDirection at the pixel centre) and the gaze ray, both in eye space.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "core/math.h"

namespace fovrt {

// The fovea disc radius (inclusive, as the disc spp model: the fovea is exactly its sppInside
// area), in pixels (a disc on the image around the gaze pixel, like the
// thesis's spp disc) or in degrees (a cone around the gaze ray).
struct FoveaRadius {
    enum class Unit { kPixels, kDegrees };
    float value = 200.0f;  // thesis: r = 200 px, the same disc as the 8-spp area
    Unit unit = Unit::kPixels;

    static FoveaRadius Pixels(float r) { return {r, Unit::kPixels}; }
    static FoveaRadius Degrees(float r) { return {r, Unit::kDegrees}; }
    // The radius in pixels of `camera`'s image (degrees at its centre's pixels per degree).
    float RadiusPixels(const EyeCamera& camera) const {
        return unit == Unit::kPixels ? value : value * camera.PixelsPerDegree();
    }
};

// One eccentricity band [minDegrees, maxDegrees).
struct EccentricityBand {
    float minDegrees = 0.0f;
    float maxDegrees = 0.0f;  // +inf for the last band
    std::string Name() const;  // "ecc0-5", "ecc20+"
};

// 0–5°, 5–10°, 10–20°, > 20°.
const std::vector<EccentricityBand>& DefaultEccentricityBands();

struct Region {
    std::string name;       // "whole", "fovea", "periphery", "ecc0-5", ...
    Plane<uint8_t> mask;    // 1 inside
    size_t pixelCount = 0;
};

class RegionSet {
public:
    // gazeEye: gaze direction in eye space (any length, z < 0 looks into the image).
    static RegionSet Build(const EyeCamera& camera, const vec3& gazeEye, const FoveaRadius& fovea = {},
                           const std::vector<EccentricityBand>& bands = DefaultEccentricityBands());

    const std::vector<Region>& regions() const { return regions_; }
    // Appends a region given by its own mask (e.g. "detail": the surfaces with roughness or
    // metallic maps, issue #13); an all-zero mask adds nothing.
    void AddMask(const std::string& name, const Plane<uint8_t>& mask);
    // nullptr when absent.
    const Region* Find(const std::string& name) const;
    // Per-pixel eccentricity in degrees.
    const Plane<float>& eccentricityDegrees() const { return eccentricity_; }
    // The continuous pixel the gaze ray hits (may lie outside the image).
    vec2 gazePixel() const { return gazePixel_; }

private:
    std::vector<Region> regions_;
    Plane<float> eccentricity_;
    vec2 gazePixel_{0.0f};
};

}  // namespace fovrt
