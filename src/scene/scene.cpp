// Time-varying scene state (keyframes, switching), texture lookup and scene-name resolution.
#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/data_dir.h"
#include "core/error.h"
#include "core/nearest_name.h"

namespace fovrt {
namespace {

// Maps `time` into the key range: clamped, or wrapped with period = last key time when looping.
float KeyTime(float time, float lastKeyTime, bool loop) {
    if (!std::isfinite(time)) return 0.0f;
    if (loop && lastKeyTime > 0.0f) {
        float t = std::fmod(time, lastKeyTime);
        return t < 0.0f ? t + lastKeyTime : t;
    }
    return time;
}

// Index i and fraction f such that time lies between keys[i] and keys[i + 1] (keys sorted by
// time). Before the first key / after the last: the end key with f = 0.
template <typename Key>
std::pair<size_t, float> Bracket(const std::vector<Key>& keys, float time) {
    if (time <= keys.front().time) return {0, 0.0f};
    if (time >= keys.back().time) return {keys.size() - 1, 0.0f};
    auto upper = std::upper_bound(keys.begin(), keys.end(), time,
                                  [](float t, const Key& k) { return t < k.time; });
    size_t i = size_t(upper - keys.begin()) - 1;
    float span = keys[i + 1].time - keys[i].time;
    float f = span > 0.0f ? (time - keys[i].time) / span : 0.0f;
    return {i, std::clamp(f, 0.0f, 1.0f)};
}

TransformKey InterpolateTransform(const std::vector<TransformKey>& keys, float time, bool loop) {
    if (keys.empty()) return TransformKey{};
    if (keys.size() == 1) return keys.front();
    auto [i, f] = Bracket(keys, KeyTime(time, keys.back().time, loop));
    if (f == 0.0f) return keys[i];
    TransformKey out;
    out.time = time;
    out.pose = Pose::Lerp(keys[i].pose, keys[i + 1].pose, f);
    out.scale = glm::mix(keys[i].scale, keys[i + 1].scale, f);
    return out;
}

mat4 MatrixOf(const TransformKey& key) {
    mat4 m = key.pose.WorldFromLocal();
    m[0] *= key.scale.x;
    m[1] *= key.scale.y;
    m[2] *= key.scale.z;
    return m;
}

int WrapIndex(int i, int n) {
    int r = i % n;
    return r < 0 ? r + n : r;
}

}  // namespace

vec4 Texture::Sample(const vec2& uv) const {
    if (width <= 0 || height <= 0 || texels.empty()) return vec4(1.0f);
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return texels.front();
    // Texel centres sit at (i + 0.5) / size; wrap the fractional coordinate first so that huge
    // uv values keep their precision.
    float x = (uv.x - std::floor(uv.x)) * float(width) - 0.5f;
    float y = (uv.y - std::floor(uv.y)) * float(height) - 0.5f;
    float fx = std::floor(x), fy = std::floor(y);
    float tx = x - fx, ty = y - fy;
    int x0 = WrapIndex(int(fx), width), x1 = WrapIndex(int(fx) + 1, width);
    int y0 = WrapIndex(int(fy), height), y1 = WrapIndex(int(fy) + 1, height);
    auto at = [&](int px, int py) { return texels[size_t(py) * size_t(width) + size_t(px)]; };
    vec4 top = glm::mix(at(x0, y0), at(x1, y0), tx);
    vec4 bottom = glm::mix(at(x0, y1), at(x1, y1), tx);
    return glm::mix(top, bottom, ty);
}

mat4 Instance::WorldFromObjectAt(float time) const {
    if (keys.empty()) return mat4(1.0f);
    return MatrixOf(InterpolateTransform(keys, time, loop));
}

bool SwitchedOn(float time, float period, float onDuration, float offset) {
    if (!(period > 0.0f)) return true;
    if (!std::isfinite(time)) return true;
    float phase = std::fmod(time - offset, period);
    if (phase < 0.0f) phase += period;
    return phase < onDuration;
}

Pose Scene::HeadAt(float time) const {
    if (cameraPath.empty()) return Pose{};
    if (cameraPath.size() == 1) return cameraPath.front().pose;
    auto [i, f] = Bracket(cameraPath, KeyTime(time, cameraPath.back().time, cameraLoop));
    if (f == 0.0f) return cameraPath[i].pose;
    return Pose::Lerp(cameraPath[i].pose, cameraPath[i + 1].pose, f);
}

SceneState Scene::StateAt(float time) const {
    SceneState state;
    state.time = time;
    state.worldFromObject.reserve(instances.size());
    for (const Instance& instance : instances)
        state.worldFromObject.push_back(instance.WorldFromObjectAt(time));
    state.emissionScale.assign(instances.size(), 1.0f);
    for (const EmissionSwitch& s : emissionSwitches) {
        if (s.instance < instances.size() && !SwitchedOn(time, s.period, s.onDuration, s.offset))
            state.emissionScale[s.instance] = 0.0f;
    }
    state.lights.reserve(lights.size());
    for (const Light& light : lights) {
        LightState ls;
        ls.type = light.type;
        bool on = SwitchedOn(time, light.switchPeriod, light.switchOnDuration, light.switchOffset);
        ls.radiantIntensity = on ? light.color * light.intensity : vec3(0.0f);
        ls.position = light.path.empty()
                          ? light.position
                          : InterpolateTransform(light.path, time, light.pathLoop).pose.position;
        ls.direction = light.direction;
        if (light.aimAtTarget) {
            vec3 d = light.target - ls.position;
            if (glm::dot(d, d) > 0.0f) ls.direction = glm::normalize(d);
        }
        ls.cosInner = std::cos(light.spotInner);
        ls.cosOuter = std::cos(light.spotOuter);
        state.lights.push_back(ls);
    }
    state.head = HeadAt(time);
    return state;
}

size_t CountTriangles(const Scene& scene) {
    size_t n = 0;
    for (const Instance& instance : scene.instances) n += scene.meshes[instance.mesh].triangles.size();
    return n;
}

size_t CountEmissiveTriangles(const Scene& scene) {
    size_t n = 0;
    for (const Instance& instance : scene.instances) {
        for (uint32_t m : scene.meshes[instance.mesh].materials) {
            const vec3& e = scene.materials[m].emission;
            if (e.x > 0.0f || e.y > 0.0f || e.z > 0.0f) ++n;
        }
    }
    return n;
}

void RequireSceneLight(const Scene& scene) {
    auto bright = [](const vec3& v) { return std::max({v.x, v.y, v.z}) > 0.0f; };
    if (CountEmissiveTriangles(scene) > 0 || bright(scene.background)) return;
    for (const Light& light : scene.lights)
        if (light.intensity > 0.0f && bright(light.color)) return;
    Fail("scene '{}' ({}): has no light (no emissive material, no [[light]] with intensity > 0, a black "
         "background): every image would be black and score as perfect",
         scene.name, scene.sourcePath.string());
}

std::filesystem::path BuiltinScenesDir() {
    if (const char* env = std::getenv("FOVRT_SCENES_DIR"); env && *env) return env;
    std::filesystem::path dir = DataRoot() / "scenes";
    return std::filesystem::exists(dir) ? dir : std::filesystem::path();
}

std::filesystem::path SharedScenesDir() {
    if (const char* env = std::getenv("FOVRT_SHARED_SCENES"); env && *env) return env;
    std::filesystem::path dir = DataRoot().parent_path() / "shared" / "scenes";
    return std::filesystem::exists(dir) ? dir : std::filesystem::path();
}

std::filesystem::path ResolveSceneName(const std::string& nameOrPath) {
    static const char* const kBuiltins[] = {"cornell",        "pillars",     "room",
                                            "veach-ajar",     "box",         "cornell-shared",
                                            "suzanne",        "brdf-detail", "brdf-detail-moving"};
    for (const char* name : kBuiltins) {
        if (nameOrPath != name) continue;
        std::filesystem::path dir = BuiltinScenesDir();
        if (dir.empty()) Fail("scene '{}': built-in scenes directory not found (set FOVRT_SCENES_DIR)", nameOrPath);
        std::filesystem::path file = dir / (nameOrPath + ".toml");
        if (!std::filesystem::exists(file)) Fail("scene '{}': {} does not exist", nameOrPath, file.string());
        return file;
    }
    std::filesystem::path path(nameOrPath);
    if (std::filesystem::exists(path)) return path;
    std::string names;
    for (const char* name : kBuiltins) names += std::string(names.empty() ? "" : ", ") + name;
    Fail("scene '{}': no such file and not a built-in scene (did you mean '{}'? built-in: {})", nameOrPath,
         NearestName(nameOrPath, kBuiltins), names);
}

bool IsStaticScene(const Scene& scene) {
    for (const Instance& instance : scene.instances)
        if (instance.keys.size() > 1) return false;
    for (const Light& light : scene.lights)
        if (light.path.size() > 1 || light.switchPeriod > 0.0f) return false;
    return scene.emissionSwitches.empty();
}

}  // namespace fovrt
