// Camera rays of the pinhole eye model (as pbrt-v4's cameras): the primary ray through a pixel
// centre and the depth gradient of the surface it hits. Primary visibility is noise-free: one
// ray through the pixel centre (render/integrator.h).
#pragma once

#include <cmath>

#include "core/camera.h"

namespace fovrt {

// Per-eye constants of the pinhole model: eye-space ray through pixel centre (x, y) is
// (tanLeft + (x + 0.5) sx, tanUp + (y + 0.5) sy, -1).
struct EyeRays {
    mat3 worldFromEye;
    mat3 eyeFromWorld;
    float tanLeft, tanUp, sx, sy;
    explicit EyeRays(const EyeCamera& camera) {
        worldFromEye = glm::mat3_cast(camera.pose().orientation);
        eyeFromWorld = glm::transpose(worldFromEye);
        const Fov& f = camera.fov();
        tanLeft = std::tan(f.angleLeft);
        tanUp = std::tan(f.angleUp);
        sx = (std::tan(f.angleRight) - tanLeft) / float(camera.width());
        sy = (std::tan(f.angleDown) - tanUp) / float(camera.height());
    }
    vec3 Eye(int x, int y) const { return vec3(tanLeft + (x + 0.5f) * sx, tanUp + (y + 0.5f) * sy, -1.0f); }
    // World-space unit primary ray direction through pixel centre (x, y).
    vec3 Direction(int x, int y) const { return glm::normalize(worldFromEye * Eye(x, y)); }
};

// Change of linear depth per pixel along x and y on the primary hit's tangent plane: with the
// eye-space ray e(x, y) (z = -1), depth = c / (n.e), so d depth / dx = -depth n_x sx / (n.e).
inline vec2 DepthGradient(const EyeRays& rays, const vec3& eyeDir, const vec3& ngWorld, float depth) {
    vec3 n = rays.eyeFromWorld * ngWorld;
    float denom = glm::dot(n, eyeDir);
    // Grazing planes: a gradient as large as the depth itself (lenient depth weights).
    if (!(std::abs(denom) > 1e-6f)) return vec2(depth);
    vec2 g(-depth * n.x * rays.sx / denom, -depth * n.y * rays.sy / denom);
    return glm::clamp(g, vec2(-depth), vec2(depth));
}

}  // namespace fovrt
