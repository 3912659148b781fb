// Programmatic scenes for the renderer tests (no files needed).
#pragma once

#include <cmath>
#include <cstring>
#include <utility>

#include "core/camera.h"
#include "core/frame_inputs.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace fovrt::test {

// UV sphere of radius r around c, geometric normals only (no vertex normals).
inline Mesh SphereMesh(const vec3& c, float r, int rings, int segments, uint32_t material) {
    Mesh m;
    m.name = "sphere";
    for (int i = 0; i <= rings; ++i) {
        float theta = kPi * float(i) / float(rings);
        for (int j = 0; j < segments; ++j) {
            float phi = 2.0f * kPi * float(j) / float(segments);
            m.positions.push_back(c + r * vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                               std::sin(theta) * std::sin(phi)));
        }
    }
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            uint32_t a = uint32_t(i * segments + j), b = uint32_t(i * segments + (j + 1) % segments);
            uint32_t c0 = a + uint32_t(segments), d = b + uint32_t(segments);
            if (i != 0) m.triangles.push_back(uvec3(a, b, d));
            if (i != rings - 1) m.triangles.push_back(uvec3(a, d, c0));
        }
    m.materials.assign(m.triangles.size(), material);
    return m;
}

// Axis-aligned quad: centre, two half-extent vectors; normal = cross(u, v).
inline void AddQuad(Mesh& m, const vec3& centre, const vec3& u, const vec3& v, uint32_t material) {
    uint32_t base = uint32_t(m.positions.size());
    m.positions.push_back(centre - u - v);
    m.positions.push_back(centre + u - v);
    m.positions.push_back(centre + u + v);
    m.positions.push_back(centre - u + v);
    m.uvs.push_back(vec2(0, 1));
    m.uvs.push_back(vec2(1, 1));
    m.uvs.push_back(vec2(1, 0));
    m.uvs.push_back(vec2(0, 0));
    m.triangles.push_back(uvec3(base, base + 1, base + 2));
    m.triangles.push_back(uvec3(base, base + 2, base + 3));
    m.materials.push_back(material);
    m.materials.push_back(material);
}

inline Scene FurnaceScene(const vec3& albedo, const vec3& le, float roughness, float metallic,
                          float specular) {
    Scene s;
    s.name = "furnace";
    Material mat;
    mat.baseColor = albedo;
    mat.emission = le;
    mat.roughness = roughness;
    mat.metallic = metallic;
    mat.specular = specular;
    s.materials.push_back(mat);
    s.meshes.push_back(SphereMesh(vec3(0.0f), 1.0f, 24, 48, 0));
    // SphereMesh faces out; the furnace is seen from inside, and area lights are one-sided.
    for (uvec3& t : s.meshes.back().triangles) std::swap(t.y, t.z);
    s.instances.push_back(Instance{"sphere", 0, {}, false});
    s.cameraPath.push_back(CameraKey{});
    return s;
}

// A closed box [-1,1]^3 (walls: 0 white lambert, 1 red, 2 green; 3 = glossy metal, 4 = emitter,
// 5 = textured) with a point light, a glossy cube (instance 1) and a ceiling emitter (instance 2).
inline Scene BoxScene(bool withEmitter = true, bool withPointLight = true) {
    Scene s;
    s.name = "box";
    Material white, red, green, metal, light, textured;
    white.baseColor = vec3(0.7f);
    white.specular = 0.0f;
    red.baseColor = vec3(0.6f, 0.1f, 0.1f);
    green.baseColor = vec3(0.1f, 0.6f, 0.1f);
    green.roughness = 0.4f;
    metal.baseColor = vec3(0.9f, 0.8f, 0.6f);
    metal.metallic = 1.0f;
    metal.roughness = 0.3f;
    light.baseColor = vec3(0.8f);
    light.emission = vec3(8.0f, 7.0f, 6.0f);
    textured.baseColor = vec3(1.0f);
    textured.baseColorTexture = 0;
    s.materials = {white, red, green, metal, light, textured};
    Texture tex;
    tex.width = tex.height = 4;
    for (int i = 0; i < 16; ++i)
        tex.texels.push_back((i + i / 4) % 2 ? vec4(0.9f, 0.9f, 0.2f, 1) : vec4(0.2f, 0.3f, 0.9f, 1));
    s.textures.push_back(tex);

    Mesh room;
    room.name = "room";
    AddQuad(room, vec3(0, -1, 0), vec3(0, 0, 1), vec3(1, 0, 0), 5);   // floor (textured)
    AddQuad(room, vec3(0, 1, 0), vec3(1, 0, 0), vec3(0, 0, 1), 0);    // ceiling
    AddQuad(room, vec3(0, 0, -1), vec3(1, 0, 0), vec3(0, 1, 0), 0);   // back
    AddQuad(room, vec3(0, 0, 1), vec3(0, 1, 0), vec3(1, 0, 0), 0);    // front (behind camera)
    AddQuad(room, vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1), 1);   // left
    AddQuad(room, vec3(1, 0, 0), vec3(0, 0, 1), vec3(0, 1, 0), 2);    // right
    s.meshes.push_back(room);

    Mesh cube;
    cube.name = "cube";
    float h = 0.3f;
    AddQuad(cube, vec3(0, h, 0), vec3(0, 0, h), vec3(h, 0, 0), 3);
    AddQuad(cube, vec3(0, -h, 0), vec3(h, 0, 0), vec3(0, 0, h), 3);
    AddQuad(cube, vec3(0, 0, h), vec3(h, 0, 0), vec3(0, h, 0), 3);
    AddQuad(cube, vec3(0, 0, -h), vec3(0, h, 0), vec3(h, 0, 0), 3);
    AddQuad(cube, vec3(h, 0, 0), vec3(0, h, 0), vec3(0, 0, h), 3);
    AddQuad(cube, vec3(-h, 0, 0), vec3(0, 0, h), vec3(0, h, 0), 3);
    s.meshes.push_back(cube);

    s.instances.push_back(Instance{"room", 0, {}, false});
    TransformKey key;
    key.pose.position = vec3(-0.3f, -0.6f, -0.3f);
    key.pose.orientation = glm::angleAxis(0.4f, vec3(0, 1, 0));
    s.instances.push_back(Instance{"cube", 1, {key}, false});

    if (withEmitter) {
        Mesh lamp;
        lamp.name = "lamp";
        AddQuad(lamp, vec3(0, 0.99f, 0), vec3(0.25f, 0, 0), vec3(0, 0, 0.25f), 4);
        s.meshes.push_back(lamp);
        s.instances.push_back(Instance{"lamp", 2, {}, false});
    }
    if (withPointLight) {
        Light l;
        l.name = "point";
        l.type = LightType::Point;
        l.position = vec3(0.4f, 0.5f, 0.2f);
        l.intensity = 2.0f;
        s.lights.push_back(l);
    }
    s.cameraPath.push_back(CameraKey{0.0f, Pose::LookAt(vec3(0, 0, 0.9f), vec3(0, -0.2f, -1))});
    return s;
}

inline EyeCamera MakeCamera(const Pose& pose, int w, int h, float hfovDeg = 70.0f) {
    return EyeCamera(pose, Fov::FromHorizontal(Radians(hfovDeg), float(w) / float(h)), w, h);
}

template <typename T>
bool BitEqual(const Plane<T>& a, const Plane<T>& b) {
    return a.width() == b.width() && a.height() == b.height() &&
           std::memcmp(a.data(), b.data(), a.bytes()) == 0;
}

}  // namespace fovrt::test
