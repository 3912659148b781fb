// Embree 3 acceleration structures for a fovrt Scene: one BLAS per mesh, one top-level scene with
// an instance per Scene::Instance whose transform follows the SceneState of the current frame.
// Also reconstructs surface data (position, normals, uv, material) from a visibility-buffer
// entry, so the renderer and the re-shading API see bit-identical surfaces.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <embree3/rtcore.h>

#include "render/renderer.h"
#include "scene/scene.h"

namespace fovrt {

struct InstanceXform {
    mat4 worldFromObject = mat4(1.0f);
    mat3 normalMatrix = mat3(1.0f);  // inverse transpose of the linear part
    float emissionScale = 1.0f;
    bool identity = true;            // skip the transforms (static scenes)
};

// Everything shading needs about one surface point.
struct SurfaceHit {
    vec3 position;       // world
    vec3 geomNormal;     // world, unit, winding orientation (not face-forwarded)
    vec3 shadingNormal;  // world, unit, same side as geomNormal
    vec2 uv;
    uint32_t material;
    float area;          // world-space triangle area
};

class EmbreeScene {
public:
    explicit EmbreeScene(const Scene& scene);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Per-frame instance transforms (also used for surface reconstruction), then commit.
    void Update(const SceneState& state);

    // Closest hit along o + t d, t in (0, tFar). Returns false on a miss.
    bool Intersect(const vec3& origin, const vec3& dir, float tFar, SurfaceSample& hit,
                   float& t, bool coherent = false) const;
    // Eight rays from one origin at once (primary rays, first bounces); valid[i] = false lanes are
    // ignored (their hits are SurfaceSample{}).
    void Intersect8(const vec3& origin, const vec3* dirs, const bool* valid, SurfaceSample* hits,
                    float* ts, bool coherent) const;
    // True when something blocks o + t d for t in (0, tFar).
    bool Occluded(const vec3& origin, const vec3& dir, float tFar) const;

    // The top-level Embree scene (the bench probe's bare rtcIntersect1 / rtcOccluded1 calls).
    RTCScene Handle() const { return top_; }

    SurfaceHit Surface(const SurfaceSample& s) const {
        SurfaceHit h;
        SurfaceInto(s, h);
        return h;
    }
    // Surface(s) written into h (the tracer's hot path: no SurfaceHit copied through the stack).
    void SurfaceInto(const SurfaceSample& s, SurfaceHit& h) const;
    // Surface with another frame's transforms (motion vectors).
    SurfaceHit SurfaceAt(const SurfaceSample& s, const std::vector<InstanceXform>& xforms) const;
    // Object-space point of a surface sample.
    vec3 ObjectPosition(const SurfaceSample& s) const;
    // World-space corners of triangle `primitive` of `instance` under `xforms`, exactly as
    // SurfaceAt computes them (so a position rebuilt from them matches it bit for bit).
    std::array<vec3, 3> WorldTriangle(uint32_t instance, uint32_t primitive,
                                      const std::vector<InstanceXform>& xforms) const;

    const std::vector<InstanceXform>& xforms() const { return xforms_; }
    static std::vector<InstanceXform> MakeXforms(const Scene& scene, const SceneState& state);

    // Bytes of the per-triangle surface records of static instances (StaticTriangle).
    size_t StaticRecordBytes() const;

private:
    // What SurfaceAt reads of one triangle of a static instance (at most one transform key),
    // gathered once at load: a hit then reads one 64-byte record (and one attribute record where
    // the mesh has normals or uvs) instead of chasing the instance, mesh, index, position, normal,
    // uv and material arrays. Every field is computed with SurfaceAt's own arithmetic on the
    // static transform, so hits are bit-identical to the general path.
    struct StaticTriangle {
        vec3 p0, e1, e2;      // world corner p0 and edges p1 - p0, p2 - p0
        vec3 geomNormal;      // cross(e1, e2) / |cross|, +z for a degenerate triangle
        float area;           // |cross| / 2
        uint32_t material;
        uint32_t flags;       // kHasNormals, kHasUvs, kTransformNormals
        uint32_t attributes;  // index into staticAttributes_ (flags say whether it is read)
    };
    static_assert(sizeof(StaticTriangle) == 64, "one cache line per static triangle");
    struct TriangleAttributes {
        vec3 normal[3];  // object space (the instance's normal matrix applies after interpolation)
        vec2 uv[3];
    };
    static constexpr uint32_t kHasNormals = 1u, kHasUvs = 2u, kTransformNormals = 4u;
    static constexpr uint32_t kNotStatic = 0xFFFFFFFFu;
    void BuildStaticRecords();
    void StaticSurface(const StaticTriangle& t, const SurfaceSample& s, SurfaceHit& h) const;

    // Scene instance of a hit: flattened static geometry reports it as the geometry ID.
    uint32_t InstanceOf(unsigned instID, unsigned geomID) const {
        return instID == RTC_INVALID_GEOMETRY_ID || instID == staticGroupId_ ? geomID : instID;
    }

    const Scene& scene_;
    unsigned staticGroupId_ = RTC_INVALID_GEOMETRY_ID;
    RTCDevice device_ = nullptr;
    RTCScene top_ = nullptr;
    std::vector<RTCScene> blas_;
    std::vector<RTCGeometry> instances_;
    std::vector<InstanceXform> xforms_;
    struct StaticRange {
        uint32_t first = kNotStatic, count = 0;  // the instance's StaticTriangles
    };
    std::vector<StaticRange> staticRanges_;  // per instance; first = kNotStatic for animated ones
    std::vector<StaticTriangle> staticTriangles_;
    std::vector<TriangleAttributes> staticAttributes_;
};

// Moves a ray origin off a surface along the geometric normal, by an amount that scales with the
// magnitude of the position (Wächter & Binder, Ray Tracing Gems ch. 6).
vec3 OffsetRayOrigin(const vec3& p, const vec3& n);

}  // namespace fovrt
