// Scene: geometry, materials, textures, lights, camera path and animation, as loaded from a scene
// description (TOML) that names mesh files (OBJ+MTL or glTF 2.0). Time-varying state (rigid
// instance motion, moving/switching lights, camera path) is evaluated per frame with
// Scene::StateAt(), so the renderer and the motion vectors see the same transforms.
// Adding a field to any struct here? Add it to SerializeScene (scene/scene_serialize.cpp), the
// stream the reference-cache key hashes; that file stops compiling until you do.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/math.h"

namespace fovrt {

// Linear-RGB texture, texels already decoded from sRGB where the format says so.
struct Texture {
    std::string path;
    int width = 0;
    int height = 0;
    std::vector<vec4> texels;  // row 0 at the top of the image

    // Bilinear lookup with wrap-around. uv follows glTF: (0,0) is the top-left texel; the OBJ
    // loader flips v so every mesh uses this one convention.
    vec4 Sample(const vec2& uv) const;
};

// Lambertian + GGX (metallic/roughness) material, glTF-style parameters.
struct Material {
    std::string name;
    vec3 baseColor = vec3(0.8f);
    int baseColorTexture = -1;          // index into Scene::textures
    float roughness = 1.0f;             // perceptual roughness, alpha = roughness²
    float metallic = 0.0f;
    int metallicRoughnessTexture = -1;  // glTF: G = roughness, B = metallic
    int roughnessTexture = -1;          // scene-file roughness map: R (linear) scales roughness
    int metallicTexture = -1;           // scene-file metallic map: R (linear) scales metallic
    float specular = 1.0f;              // dielectric specular weight: F0 = 0.04·specular (0 = pure Lambert)
    vec3 emission = vec3(0.0f);         // emitted radiance (W/(m²·sr)), area light if non-zero
    // Emission leaves only the front side (SurfaceHit::geomNormal's) unless this is set, as in
    // pbrt and Mitsuba: a light panel does not light the ceiling it hangs under.
    bool emissionTwoSided = false;
};

// Triangle mesh in object space.
struct Mesh {
    std::string name;
    std::vector<vec3> positions;
    std::vector<vec3> normals;      // per vertex, may be empty (then geometric normals)
    std::vector<vec2> uvs;          // per vertex, may be empty
    std::vector<uvec3> triangles;   // vertex indices
    std::vector<uint32_t> materials;  // per triangle, index into Scene::materials
};

// Piecewise-linear keyframes of a rigid transform (slerp on rotation).
struct TransformKey {
    float time = 0.0f;  // seconds
    Pose pose;
    vec3 scale = vec3(1.0f);
};

struct Instance {
    std::string name;
    uint32_t mesh = 0;                 // index into Scene::meshes
    std::vector<TransformKey> keys;    // empty: identity; one key: static
    bool loop = false;                 // repeat the keys with period = last key time
    mat4 WorldFromObjectAt(float time) const;
};

enum class LightType { Point, Spot, Directional };

// Analytic light. Area lights are not listed here: they are emissive triangles.
struct Light {
    std::string name;
    LightType type = LightType::Point;
    vec3 color = vec3(1.0f);
    float intensity = 1.0f;            // W/sr for point/spot, W/m² (irradiance) for directional
    vec3 position = vec3(0.0f);
    vec3 direction = vec3(0, -1, 0);   // spot/directional: direction the light travels
    float spotInner = Radians(20.0f);  // spot cone half-angles
    float spotOuter = Radians(30.0f);
    std::vector<TransformKey> path;    // optional motion of position (key pose positions)
    bool pathLoop = false;             // repeat the path with period = last key time
    // Spot/directional aimed at a point: direction = normalize(target - position(t)).
    bool aimAtTarget = false;
    vec3 target = vec3(0.0f);
    // On/off switching: the light is on when fmod(time - offset, period) < onDuration
    // (period 0: always on). See SwitchedOn().
    float switchPeriod = 0.0f;
    float switchOnDuration = 0.0f;
    float switchOffset = 0.0f;         // time shift of the schedule
};

// Per-frame evaluated state.
struct LightState {
    LightType type;
    vec3 radiantIntensity;  // color * intensity, 0 when switched off
    vec3 position;
    vec3 direction;
    float cosInner, cosOuter;
};

struct SceneState {
    float time = 0.0f;
    std::vector<mat4> worldFromObject;   // one per instance
    std::vector<LightState> lights;      // one per Scene::lights entry
    // Scale of each instance's emission at this time (1 normally; 0 while an emissive object
    // is switched off). One per instance.
    std::vector<float> emissionScale;
    Pose head;                           // camera/head pose from the camera path
};

struct CameraKey {
    float time = 0.0f;
    Pose pose;
};

struct Scene {
    std::string name;
    std::filesystem::path sourcePath;   // the scene file it came from
    // Every file the load read (scene file, meshes, MTLs, glTF buffers and images, textures), once
    // each, in the order read: what a content check of the scene's files hashes.
    std::vector<std::filesystem::path> files;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Instance> instances;
    std::vector<Light> lights;
    // Emissive-instance switching (flickering area lights): instance index + schedule.
    struct EmissionSwitch {
        uint32_t instance;
        float period, onDuration, offset;
    };
    std::vector<EmissionSwitch> emissionSwitches;
    std::vector<CameraKey> cameraPath;  // at least one key (the static camera)
    bool cameraLoop = false;            // repeat the camera path with period = last key time
    float horizontalFovDegrees = 60.0f; // default symmetric per-eye FOV when config gives none
    float frameRate = 30.0f;            // frames per second: time = frame / frameRate
    vec3 background = vec3(0.0f);       // radiance of escaped rays

    SceneState StateAt(float time) const;
    Pose HeadAt(float time) const;
};

// Loads a scene description (.toml) or, for convenience, a bare mesh (.obj/.gltf/.glb) with a
// default camera. Throws fovrt::Error naming the file/key/line on any problem.
Scene LoadScene(const std::filesystem::path& path);

// Directory with the built-in scenes shipped in the repository (scenes/ under core/data_dir.h's
// DataRoot: the installed copy or the source tree), and the shared assets (../shared/scenes beside
// that folder), or empty paths when absent.
std::filesystem::path BuiltinScenesDir();
std::filesystem::path SharedScenesDir();

// Resolves a built-in name ("cornell", "pillars", "room" in BuiltinScenesDir(); "cornell-shared",
// "veach-ajar", "box", "suzanne": scene files in BuiltinScenesDir() that reference the shared
// assets) or a path to a scene/mesh file. Throws fovrt::Error for an unknown name or missing file.
std::filesystem::path ResolveSceneName(const std::string& nameOrPath);

// The switching schedule shared by lights and emissive instances: on while
// fmod(time - offset, period) (taken in [0, period)) < onDuration; always on when period <= 0.
bool SwitchedOn(float time, float period, float onDuration, float offset);

// Number of triangles whose material emits (emission > 0), over all instances.
size_t CountEmissiveTriangles(const Scene& scene);
size_t CountTriangles(const Scene& scene);

// Refuses a scene no image of which can show anything: no emissive triangle, no [[light]] with
// colour × intensity > 0 and a black background render every frame black, which every metric
// then scores as perfect (relMSE 0, JOD 10). Throws fovrt::Error naming the scene and its file.
// Called where a scene is loaded to be rendered (FramePipeline); LoadScene itself does not ask
// for light, so tools and tests may load bare geometry.
void RequireSceneLight(const Scene& scene);

// True when nothing in the scene changes with time (no instance motion, moving or switching
// lights, flickering emitters). The camera path is not part of this: it moves the eyes only.
bool IsStaticScene(const Scene& scene);

}  // namespace fovrt
