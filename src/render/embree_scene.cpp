#include "render/embree_scene.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/check.h"
#include "core/error.h"
#include "render/embree_rays.h"

namespace fovrt {
namespace {

void ErrorCallback(void*, RTCError code, const char* message) {
    // Embree reports programming errors here; they are invariant violations for us.
    ::fovrt::detail::CheckFailed(__FILE__, __LINE__,
                                 fmt::format("embree error {}: {}", int(code), message ? message : ""));
}

}  // namespace

vec3 OffsetRayOrigin(const vec3& p, const vec3& n) {
    constexpr float kOrigin = 1.0f / 32.0f;
    constexpr float kFloatScale = 1.0f / 65536.0f;
    constexpr float kIntScale = 256.0f;
    vec3 out;
    for (int i = 0; i < 3; ++i) {
        int offset = int(kIntScale * n[i]);
        int32_t bits = std::bit_cast<int32_t>(p[i]) + (p[i] < 0.0f ? -offset : offset);
        float moved = std::bit_cast<float>(bits);
        out[i] = std::abs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : moved;
    }
    return out;
}

// BVH quality of everything that does not move. MEDIUM, not HIGH (spatial splits): on
// veach-ajar MEDIUM traced 5-18 % more rays per second and built faster, with the same hits (same
// image checksums); on the 36-triangle Cornell box no difference (PROFILE.md, fourth pass).
constexpr RTCBuildQuality kStaticBuildQuality = RTC_BUILD_QUALITY_MEDIUM;

EmbreeScene::EmbreeScene(const Scene& scene) : scene_(scene) {
    device_ = rtcNewDevice(nullptr);
    if (!device_) Fail("embree: cannot create a device (error {})", int(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(device_, ErrorCallback, nullptr);

    // Triangle geometry of a mesh, optionally with its vertices baked into world space.
    auto makeTriangles = [&](const Mesh& mesh, const mat4* worldFromObject) -> RTCGeometry {
        if (mesh.triangles.empty()) return nullptr;
        RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
        for (size_t i = 0; i < mesh.positions.size(); ++i) {
            vec3 p = worldFromObject ? vec3(*worldFromObject * vec4(mesh.positions[i], 1.0f)) : mesh.positions[i];
            vertices[3 * i + 0] = p.x;
            vertices[3 * i + 1] = p.y;
            vertices[3 * i + 2] = p.z;
        }
        auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
            geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh.triangles.size()));
        for (size_t i = 0; i < mesh.triangles.size(); ++i) {
            const uvec3& t = mesh.triangles[i];
            if (t.x >= mesh.positions.size() || t.y >= mesh.positions.size() || t.z >= mesh.positions.size())
                Fail("scene {}: mesh '{}' triangle {} indexes a missing vertex", scene.name, mesh.name, i);
            indices[3 * i + 0] = t.x;
            indices[3 * i + 1] = t.y;
            indices[3 * i + 2] = t.z;
        }
        rtcSetGeometryBuildQuality(geom, kStaticBuildQuality);
        rtcCommitGeometry(geom);
        return geom;
    };

    // Static instances (at most one key) are flattened: their triangles, baked into world space,
    // go straight into the top-level scene (geometry ID = instance index) when nothing moves.
    // With animated instances they go into one static scene, instanced once with identity, so
    // the per-frame commit only rebuilds the small top level over the moving instances.
    bool animated = false;
    for (const Instance& inst : scene.instances) animated = animated || inst.keys.size() > 1;
    top_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(top_, kStaticBuildQuality);
    RTCScene staticScene = top_;
    if (animated) {
        rtcSetSceneFlags(top_, RTC_SCENE_FLAG_DYNAMIC);
        rtcSetSceneBuildQuality(top_, RTC_BUILD_QUALITY_LOW);
        staticScene = rtcNewScene(device_);
        rtcSetSceneBuildQuality(staticScene, kStaticBuildQuality);
    }
    blas_.assign(scene.meshes.size(), nullptr);
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& inst = scene.instances[i];
        if (inst.mesh >= scene.meshes.size())
            Fail("scene {}: instance '{}' names mesh {} but there are {} meshes", scene.name,
                 inst.name, inst.mesh, scene.meshes.size());
        const Mesh& mesh = scene.meshes[inst.mesh];
        if (inst.keys.size() <= 1) {
            mat4 m = inst.WorldFromObjectAt(0.0f);
            if (RTCGeometry geom = makeTriangles(mesh, &m)) {
                rtcAttachGeometryByID(staticScene, geom, unsigned(i));
                rtcReleaseGeometry(geom);
            }
            instances_.push_back(nullptr);
            continue;
        }
        // Animated instance: a BLAS per mesh (shared), transform updated per frame.
        if (!blas_[inst.mesh]) {
            RTCScene blas = rtcNewScene(device_);
            rtcSetSceneBuildQuality(blas, kStaticBuildQuality);
            if (RTCGeometry geom = makeTriangles(mesh, nullptr)) {
                rtcAttachGeometryByID(blas, geom, 0);
                rtcReleaseGeometry(geom);
            }
            rtcCommitScene(blas);
            blas_[inst.mesh] = blas;
        }
        RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(geom, blas_[inst.mesh]);
        rtcSetGeometryTimeStepCount(geom, 1);
        mat4 identity(1.0f);
        rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &identity[0][0]);
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(top_, geom, unsigned(i));
        instances_.push_back(geom);
    }
    if (staticScene != top_) {
        rtcCommitScene(staticScene);
        staticGroupId_ = unsigned(scene.instances.size());
        RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(geom, staticScene);
        rtcSetGeometryTimeStepCount(geom, 1);
        mat4 identity(1.0f);
        rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &identity[0][0]);
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(top_, geom, staticGroupId_);
        rtcReleaseGeometry(geom);
        blas_.push_back(staticScene);  // released with the BLAS
    }
    xforms_.assign(scene.instances.size(), InstanceXform{});
    rtcCommitScene(top_);
    BuildStaticRecords();
}

void EmbreeScene::BuildStaticRecords() {
    // The transform of a static instance is the same in every frame: take it from time 0.
    const std::vector<InstanceXform> xforms = MakeXforms(scene_, scene_.StateAt(0.0f));
    staticRanges_.assign(scene_.instances.size(), StaticRange{});
    size_t count = 0, withAttributes = 0;
    for (const Instance& inst : scene_.instances) {
        if (inst.keys.size() > 1) continue;
        const Mesh& mesh = scene_.meshes[inst.mesh];
        count += mesh.triangles.size();
        if (!mesh.normals.empty() || !mesh.uvs.empty()) withAttributes += mesh.triangles.size();
    }
    staticTriangles_.reserve(count);
    staticAttributes_.reserve(withAttributes);
    for (size_t i = 0; i < scene_.instances.size(); ++i) {
        const Instance& inst = scene_.instances[i];
        if (inst.keys.size() > 1) continue;
        const InstanceXform& x = xforms[i];
        const Mesh& mesh = scene_.meshes[inst.mesh];
        staticRanges_[i] = StaticRange{uint32_t(staticTriangles_.size()), uint32_t(mesh.triangles.size())};
        for (size_t k = 0; k < mesh.triangles.size(); ++k) {
            const uvec3& tri = mesh.triangles[k];
            // As SurfaceAt: corners, then edges and the cross product of the edges.
            const auto [p0, p1, p2] = WorldTriangle(uint32_t(i), uint32_t(k), xforms);
            StaticTriangle t;
            t.p0 = p0;
            t.e1 = p1 - p0;
            t.e2 = p2 - p0;
            vec3 c = glm::cross(t.e1, t.e2);
            float len = glm::length(c);
            t.area = 0.5f * len;
            t.geomNormal = len > 0.0f ? c / len : vec3(0.0f, 0.0f, 1.0f);
            t.material = mesh.materials.empty() ? 0u : mesh.materials[k];
            t.flags = (mesh.normals.empty() ? 0u : kHasNormals) | (mesh.uvs.empty() ? 0u : kHasUvs) |
                      (x.identity ? 0u : kTransformNormals);
            t.attributes = 0;
            if (!mesh.normals.empty() || !mesh.uvs.empty()) {
                TriangleAttributes a{};
                for (int corner = 0; corner < 3; ++corner) {
                    if (!mesh.normals.empty()) a.normal[corner] = mesh.normals[tri[corner]];
                    if (!mesh.uvs.empty()) a.uv[corner] = mesh.uvs[tri[corner]];
                }
                t.attributes = uint32_t(staticAttributes_.size());
                staticAttributes_.push_back(a);
            }
            staticTriangles_.push_back(t);
        }
    }
}

size_t EmbreeScene::StaticRecordBytes() const {
    return staticTriangles_.size() * sizeof(StaticTriangle) + staticAttributes_.size() * sizeof(TriangleAttributes);
}

EmbreeScene::~EmbreeScene() {
    for (RTCGeometry g : instances_)
        if (g) rtcReleaseGeometry(g);
    if (top_) rtcReleaseScene(top_);
    for (RTCScene s : blas_)
        if (s) rtcReleaseScene(s);
    if (device_) rtcReleaseDevice(device_);
}

std::vector<InstanceXform> EmbreeScene::MakeXforms(const Scene& scene, const SceneState& state) {
    std::vector<InstanceXform> xforms(scene.instances.size());
    for (size_t i = 0; i < xforms.size(); ++i) {
        InstanceXform& x = xforms[i];
        x.worldFromObject = i < state.worldFromObject.size() ? state.worldFromObject[i] : mat4(1.0f);
        x.normalMatrix = glm::transpose(glm::inverse(mat3(x.worldFromObject)));
        x.emissionScale = i < state.emissionScale.size() ? state.emissionScale[i] : 1.0f;
        x.identity = x.worldFromObject == mat4(1.0f);
    }
    return xforms;
}

void EmbreeScene::Update(const SceneState& state) {
    xforms_ = MakeXforms(scene_, state);
    for (size_t i = 0; i < instances_.size(); ++i) {
        if (!instances_[i]) continue;  // static, flattened
        rtcSetGeometryTransform(instances_[i], 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR,
                                &xforms_[i].worldFromObject[0][0]);
        rtcCommitGeometry(instances_[i]);
    }
    rtcCommitScene(top_);
}

bool EmbreeScene::Intersect(const vec3& origin, const vec3& dir, float tFar, SurfaceSample& hit,
                            float& t, bool coherent) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    RTCRayHit rh;
    InitRay(rh.ray, origin, dir, tFar);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(top_, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit.instance = InstanceOf(rh.hit.instID[0], rh.hit.geomID);
    hit.primitive = rh.hit.primID;
    hit.barycentrics = vec2(rh.hit.u, rh.hit.v);
    t = rh.ray.tfar;
    return true;
}

void EmbreeScene::Intersect8(const vec3& origin, const vec3* dirs, const bool* valid,
                             SurfaceSample* hits, float* ts, bool coherent) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    alignas(32) int mask[8];
    alignas(32) RTCRayHit8 rh;
    InitRayPacket8(origin, dirs, valid, mask, rh);
    rtcIntersect8(mask, top_, &context, &rh);
    for (int i = 0; i < 8; ++i) {
        if (!valid[i] || rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) {
            hits[i] = SurfaceSample{};
            ts[i] = std::numeric_limits<float>::infinity();
            continue;
        }
        hits[i].instance = InstanceOf(rh.hit.instID[0][i], rh.hit.geomID[i]);
        hits[i].primitive = rh.hit.primID[i];
        hits[i].barycentrics = vec2(rh.hit.u[i], rh.hit.v[i]);
        ts[i] = rh.ray.tfar[i];
    }
}

bool EmbreeScene::Occluded(const vec3& origin, const vec3& dir, float tFar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    RTCRay ray;
    InitRay(ray, origin, dir, tFar);
    rtcOccluded1(top_, &context, &ray);
    return ray.tfar == -std::numeric_limits<float>::infinity();
}

vec3 EmbreeScene::ObjectPosition(const SurfaceSample& s) const {
    const Mesh& mesh = scene_.meshes[scene_.instances[s.instance].mesh];
    const uvec3& tri = mesh.triangles[s.primitive];
    vec3 p0 = mesh.positions[tri.x], p1 = mesh.positions[tri.y], p2 = mesh.positions[tri.z];
    return p0 + s.barycentrics.x * (p1 - p0) + s.barycentrics.y * (p2 - p0);
}

std::array<vec3, 3> EmbreeScene::WorldTriangle(uint32_t instance, uint32_t primitive,
                                               const std::vector<InstanceXform>& xforms) const {
    FOVRT_CHECK_OP(instance, <, scene_.instances.size());
    const InstanceXform& x = xforms[instance];
    const Mesh& mesh = scene_.meshes[scene_.instances[instance].mesh];
    FOVRT_CHECK_OP(primitive, <, mesh.triangles.size());
    const uvec3& tri = mesh.triangles[primitive];
    std::array<vec3, 3> p = {mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z]};
    if (!x.identity)
        for (vec3& corner : p) corner = vec3(x.worldFromObject * vec4(corner, 1.0f));
    return p;
}

// SurfaceAt for a triangle of a static instance, from its record: the same operations on the
// same values, in the same order.
void EmbreeScene::StaticSurface(const StaticTriangle& t, const SurfaceSample& s, SurfaceHit& h) const {
    float u = s.barycentrics.x, v = s.barycentrics.y, w = 1.0f - u - v;
    h.position = t.p0 + u * t.e1 + v * t.e2;
    h.area = t.area;
    h.geomNormal = t.geomNormal;
    h.shadingNormal = h.geomNormal;
    const TriangleAttributes* a = (t.flags & (kHasNormals | kHasUvs)) ? &staticAttributes_[t.attributes] : nullptr;
    if (t.flags & kHasNormals) {
        vec3 n = w * a->normal[0] + u * a->normal[1] + v * a->normal[2];
        if (t.flags & kTransformNormals) n = xforms_[s.instance].normalMatrix * n;
        float nlen = glm::length(n);
        if (nlen > 0.0f && std::isfinite(nlen)) {
            h.shadingNormal = n / nlen;
            if (glm::dot(h.shadingNormal, h.geomNormal) < 0.0f) h.geomNormal = -h.geomNormal;
        }
    }
    h.uv = (t.flags & kHasUvs) ? w * a->uv[0] + u * a->uv[1] + v * a->uv[2] : vec2(u, v);
    h.material = t.material;
}

void EmbreeScene::SurfaceInto(const SurfaceSample& s, SurfaceHit& h) const {
    FOVRT_CHECK_OP(s.instance, <, scene_.instances.size());
    if (const StaticRange& r = staticRanges_[s.instance]; r.first != kNotStatic) {
        FOVRT_CHECK_OP(s.primitive, <, r.count);
        StaticSurface(staticTriangles_[r.first + s.primitive], s, h);
        return;
    }
    h = SurfaceAt(s, xforms_);
}

SurfaceHit EmbreeScene::SurfaceAt(const SurfaceSample& s, const std::vector<InstanceXform>& xforms) const {
    FOVRT_CHECK_OP(s.instance, <, scene_.instances.size());
    // A static instance's transform is the same in every frame's xforms: its record serves all.
    if (const StaticRange& r = staticRanges_[s.instance]; r.first != kNotStatic) {
        FOVRT_CHECK_OP(s.primitive, <, r.count);
        SurfaceHit h;
        StaticSurface(staticTriangles_[r.first + s.primitive], s, h);
        return h;
    }
    const InstanceXform& x = xforms[s.instance];
    const Mesh& mesh = scene_.meshes[scene_.instances[s.instance].mesh];
    const auto [p0, p1, p2] = WorldTriangle(s.instance, s.primitive, xforms);
    const uvec3& tri = mesh.triangles[s.primitive];
    float u = s.barycentrics.x, v = s.barycentrics.y, w = 1.0f - u - v;
    SurfaceHit h;
    h.position = p0 + u * (p1 - p0) + v * (p2 - p0);
    vec3 c = glm::cross(p1 - p0, p2 - p0);
    float len = glm::length(c);
    h.area = 0.5f * len;
    h.geomNormal = len > 0.0f ? c / len : vec3(0.0f, 0.0f, 1.0f);
    h.shadingNormal = h.geomNormal;
    if (!mesh.normals.empty()) {
        vec3 n = w * mesh.normals[tri.x] + u * mesh.normals[tri.y] + v * mesh.normals[tri.z];
        if (!x.identity) n = x.normalMatrix * n;
        float nlen = glm::length(n);
        if (nlen > 0.0f && std::isfinite(nlen)) {
            h.shadingNormal = n / nlen;
            // Authored normals define the front side; keep the geometric normal on it.
            if (glm::dot(h.shadingNormal, h.geomNormal) < 0.0f) h.geomNormal = -h.geomNormal;
        }
    }
    h.uv = mesh.uvs.empty() ? vec2(u, v)
                            : w * mesh.uvs[tri.x] + u * mesh.uvs[tri.y] + v * mesh.uvs[tri.z];
    h.material = mesh.materials.empty() ? 0u : mesh.materials[s.primitive];
    return h;
}

}  // namespace fovrt
