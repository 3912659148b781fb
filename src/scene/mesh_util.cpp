// Mesh validation and normal completion shared by the OBJ and glTF loaders.
#include <cmath>

#include "core/error.h"
#include "scene/loaders.h"

namespace fovrt::detail {

void FinishMesh(Mesh& mesh, const std::string& file) {
    const size_t nv = mesh.positions.size();
    for (size_t i = 0; i < nv; ++i) {
        if (!IsFinite(mesh.positions[i]))
            Fail("{}: vertex {} of mesh '{}' is not finite ({}, {}, {})", file, i, mesh.name,
                 mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z);
    }
    if (!mesh.uvs.empty()) {
        if (mesh.uvs.size() != nv) Fail("{}: mesh '{}' has {} uvs for {} vertices", file, mesh.name, mesh.uvs.size(), nv);
        for (size_t i = 0; i < nv; ++i) {
            if (!std::isfinite(mesh.uvs[i].x) || !std::isfinite(mesh.uvs[i].y))
                Fail("{}: texture coordinate {} of mesh '{}' is not finite", file, i, mesh.name);
        }
    }
    if (mesh.materials.size() != mesh.triangles.size())
        Fail("{}: mesh '{}' has {} material ids for {} triangles", file, mesh.name, mesh.materials.size(),
             mesh.triangles.size());
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const uvec3& tri = mesh.triangles[t];
        if (tri.x >= nv || tri.y >= nv || tri.z >= nv)
            Fail("{}: triangle {} of mesh '{}' has a vertex index out of range ({}, {}, {}; {} vertices)",
                 file, t, mesh.name, tri.x, tri.y, tri.z, nv);
    }
    if (mesh.normals.empty()) return;
    if (mesh.normals.size() != nv) Fail("{}: mesh '{}' has {} normals for {} vertices", file, mesh.name, mesh.normals.size(), nv);
    // Missing (zero) or non-finite normals: area-weighted face normals of the vertex's triangles.
    std::vector<bool> fill(nv, false);
    bool any = false;
    for (size_t i = 0; i < nv; ++i) {
        vec3& n = mesh.normals[i];
        float len2 = IsFinite(n) ? glm::dot(n, n) : 0.0f;
        if (!(len2 > 1e-20f) || !std::isfinite(len2)) {
            fill[i] = true;
            any = true;
            n = vec3(0.0f);
        } else {
            n /= std::sqrt(len2);
        }
    }
    if (!any) return;
    for (const uvec3& tri : mesh.triangles) {
        vec3 a = mesh.positions[tri.x], b = mesh.positions[tri.y], c = mesh.positions[tri.z];
        vec3 faceNormal = glm::cross(b - a, c - a);  // length = 2 * area
        for (uint32_t v : {tri.x, tri.y, tri.z})
            if (fill[v]) mesh.normals[v] += faceNormal;
    }
    for (size_t i = 0; i < nv; ++i) {
        if (!fill[i]) continue;
        float len = glm::length(mesh.normals[i]);
        mesh.normals[i] = (len > 0.0f && std::isfinite(len)) ? mesh.normals[i] / len : vec3(0, 1, 0);
    }
}

}  // namespace fovrt::detail
