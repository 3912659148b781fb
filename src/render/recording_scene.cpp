#include "render/recording_scene.h"

#include <limits>

#include "render/embree_rays.h"

namespace fovrt {

bool RecordingScene::Intersect(const vec3& origin, const vec3& dir, float tFar, SurfaceSample& hit, float& t,
                               bool coherent) const {
    if (log_) Log(origin, dir, tFar, false);
    return scene_.Intersect(origin, dir, tFar, hit, t, coherent);
}

void RecordingScene::Intersect8(const vec3& origin, const vec3* dirs, const bool* valid, SurfaceSample* hits,
                                float* ts, bool coherent) const {
    if (log_)
        for (int i = 0; i < 8; ++i)
            if (valid[i]) Log(origin, dirs[i], std::numeric_limits<float>::infinity(), false);
    scene_.Intersect8(origin, dirs, valid, hits, ts, coherent);
}

bool RecordingScene::Occluded(const vec3& origin, const vec3& dir, float tFar) const {
    if (log_) Log(origin, dir, tFar, true);
    return scene_.Occluded(origin, dir, tFar);
}

void RecordingScene::Log(const vec3& origin, const vec3& dir, float tFar, bool shadow) const {
    std::lock_guard<std::mutex> lock(mutex_);
    log_->push_back(TracedRay{origin, dir, tFar, shadow});
}

bool TraceBare(const EmbreeScene& scene, const TracedRay& r) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    if (r.shadow) {
        RTCRay ray;
        InitRay(ray, r.origin, r.dir, r.tFar);
        rtcOccluded1(scene.Handle(), &context, &ray);
        return ray.tfar == -std::numeric_limits<float>::infinity();
    }
    RTCRayHit rh;
    InitRay(rh.ray, r.origin, r.dir, r.tFar);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene.Handle(), &context, &rh);
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

}  // namespace fovrt
