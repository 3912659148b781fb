#include "metrics/regions.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.h"
#include "metrics/filter.h"

namespace fovrt {

namespace {

float AngleDegrees(const vec3& a, const vec3& b) {
    // atan2 of |a×b| and a·b stays accurate near 0°, unlike acos.
    return Degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

}  // namespace

std::string EccentricityBand::Name() const {
    if (!std::isfinite(maxDegrees)) return fmt::format("ecc{:g}+", minDegrees);
    return fmt::format("ecc{:g}-{:g}", minDegrees, maxDegrees);
}

const std::vector<EccentricityBand>& DefaultEccentricityBands() {
    static const std::vector<EccentricityBand> bands = {
        {0.0f, 5.0f}, {5.0f, 10.0f}, {10.0f, 20.0f}, {20.0f, std::numeric_limits<float>::infinity()}};
    return bands;
}

RegionSet RegionSet::Build(const EyeCamera& camera, const vec3& gazeEye, const FoveaRadius& fovea,
                           const std::vector<EccentricityBand>& bands) {
    const int w = camera.width(), h = camera.height();
    FOVRT_CHECK(w > 0 && h > 0);
    if (!(glm::length(gazeEye) > 0.0f) || !IsFinite(gazeEye))
        Fail("regions: gaze direction ({}, {}, {}) is not a direction", gazeEye.x, gazeEye.y, gazeEye.z);
    if (!(fovea.value >= 0.0f)) Fail("regions: fovea radius {} must be >= 0", fovea.value);
    const vec3 gaze = glm::normalize(gazeEye);

    RegionSet set;
    // A gaze that looks backwards has no image position; its disc is empty.
    const bool gazeOnImagePlane = gaze.z < 0.0f;
    set.gazePixel_ = gazeOnImagePlane ? camera.PixelOfEyeDirection(gaze)
                                      : vec2(std::numeric_limits<float>::infinity());
    set.eccentricity_.Resize(w, h);

    Region whole{"whole", Plane<uint8_t>(w, h, 1), 0};
    Region foveaRegion{"fovea", Plane<uint8_t>(w, h, 0), 0};
    Region periphery{"periphery", Plane<uint8_t>(w, h, 0), 0};
    std::vector<Region> bandRegions;
    for (const EccentricityBand& b : bands) bandRegions.push_back({b.Name(), Plane<uint8_t>(w, h, 0), 0});

    const float r2 = fovea.value * fovea.value;
    metrics_detail::ParallelRows(h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
            const float ecc = AngleDegrees(camera.EyeDirection(centre), gaze);
            set.eccentricity_(x, y) = ecc;
            bool inFovea;
            if (fovea.unit == FoveaRadius::Unit::kDegrees) {
                inFovea = ecc <= fovea.value;
            } else {
                const vec2 d = centre - set.gazePixel_;
                inFovea = gazeOnImagePlane && glm::dot(d, d) <= r2;
            }
            (inFovea ? foveaRegion : periphery).mask(x, y) = 1;
            for (size_t b = 0; b < bands.size(); ++b)
                if (ecc >= bands[b].minDegrees && ecc < bands[b].maxDegrees) bandRegions[b].mask(x, y) = 1;
        }
    });

    set.regions_.push_back(std::move(whole));
    set.regions_.push_back(std::move(foveaRegion));
    set.regions_.push_back(std::move(periphery));
    for (Region& r : bandRegions) set.regions_.push_back(std::move(r));
    for (Region& r : set.regions_) r.pixelCount = size_t(std::count(r.mask.vector().begin(), r.mask.vector().end(), uint8_t(1)));
    return set;
}

const Region* RegionSet::Find(const std::string& name) const {
    for (const Region& r : regions_)
        if (r.name == name) return &r;
    return nullptr;
}

void RegionSet::AddMask(const std::string& name, const Plane<uint8_t>& mask) {
    Region r{name, mask, 0};
    for (size_t i = 0; i < mask.size(); ++i) r.pixelCount += mask[i] ? 1 : 0;
    if (r.pixelCount > 0) regions_.push_back(std::move(r));
}

}  // namespace fovrt
