// The probe renderer's way to Embree (render/probes.h): the EmbreeScene ray calls the tracer
// makes, each appended to a log first while one is set. Only the probe instantiation of the tracer
// traces through it; the production tracer calls EmbreeScene itself, so its rays pay nothing for
// the probe (before, a branch per ray in EmbreeScene).
#pragma once

#include <mutex>
#include <vector>

#include "render/embree_scene.h"
#include "render/probes.h"

namespace fovrt {

class RecordingScene {
public:
    explicit RecordingScene(const EmbreeScene& scene) : scene_(scene) {}

    // Appends every ray traced from now on to `log` (nullptr: stop); see ProbeRenderer::RecordRays.
    void SetLog(std::vector<TracedRay>* log) { log_ = log; }

    // EmbreeScene's calls, logged.
    bool Intersect(const vec3& origin, const vec3& dir, float tFar, SurfaceSample& hit, float& t,
                   bool coherent = false) const;
    void Intersect8(const vec3& origin, const vec3* dirs, const bool* valid, SurfaceSample* hits, float* ts,
                    bool coherent) const;
    bool Occluded(const vec3& origin, const vec3& dir, float tFar) const;

private:
    void Log(const vec3& origin, const vec3& dir, float tFar, bool shadow) const;

    const EmbreeScene& scene_;
    std::vector<TracedRay>* log_ = nullptr;
    mutable std::mutex mutex_;
};

// rtcIntersect1 / rtcOccluded1 on one recorded ray, nothing else; true on a hit.
bool TraceBare(const EmbreeScene& scene, const TracedRay& ray);

}  // namespace fovrt
