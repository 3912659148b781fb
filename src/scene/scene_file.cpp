// LoadScene(): the TOML scene description (format in scenes/README.md) or a bare mesh file.
// Every key is checked: unknown keys, wrong types and bad values throw fovrt::Error naming the
// file, the key and its line.
#include <algorithm>
#include <cmath>
#include <set>

#include <toml++/toml.h>

#include "core/error.h"
#include "scene/loaders.h"

namespace fovrt {
namespace {

using detail::LoadContext;
using detail::MeshPart;

// Reads one TOML table, remembering which keys were consumed so that Finish() can reject the
// rest. `where` is the table's dotted path for messages ("mesh[1].keys[0]").
class TableReader {
public:
    TableReader(const toml::table& table, std::string where, const std::string& file)
        : table_(table), where_(std::move(where)), file_(file) {}

    const std::string& where() const { return where_; }
    const std::string& file() const { return file_; }
    bool Has(const std::string& key) const { return table_.contains(key); }

    [[noreturn]] void FailAt(const std::string& key, const std::string& message) const {
        const toml::node* node = table_.get(key);
        int line = node ? int(node->source().begin.line) : int(table_.source().begin.line);
        Fail("{}:{}: {}: {}", file_, line, Key(key), message);
    }

    std::string Key(const std::string& key) const { return where_.empty() ? key : where_ + "." + key; }

    std::optional<double> Number(const std::string& key) {
        const toml::node* node = Take(key);
        if (!node) return std::nullopt;
        double v;
        if (auto i = node->value_exact<int64_t>()) v = double(*i);
        else if (auto d = node->value_exact<double>()) v = *d;
        else FailAt(key, "expected a number");
        if (!std::isfinite(v) || std::fabs(v) > 1e30) FailAt(key, "expected a finite number");
        return v;
    }
    float Float(const std::string& key, float fallback, float lo = -1e30f, float hi = 1e30f) {
        auto v = Number(key);
        if (!v) return fallback;
        if (*v < lo || *v > hi) FailAt(key, fmt::format("value {} outside [{}, {}]", *v, lo, hi));
        return float(*v);
    }
    std::optional<std::string> String(const std::string& key) {
        const toml::node* node = Take(key);
        if (!node) return std::nullopt;
        auto s = node->value_exact<std::string>();
        if (!s) FailAt(key, "expected a string");
        return *s;
    }
    std::optional<bool> Bool(const std::string& key) {
        const toml::node* node = Take(key);
        if (!node) return std::nullopt;
        auto b = node->value_exact<bool>();
        if (!b) FailAt(key, "expected true or false");
        return *b;
    }
    // [x, y, z]; `scalarOk` also accepts one number for all three.
    std::optional<vec3> Vec3(const std::string& key, bool scalarOk = false) {
        const toml::node* node = table_.get(key);
        if (node && scalarOk && node->is_number()) {
            float v = float(*Number(key));
            return vec3(v);
        }
        auto values = Numbers(key);
        if (!values) return std::nullopt;
        if (values->size() != 3) FailAt(key, "expected [x, y, z]");
        return vec3(float((*values)[0]), float((*values)[1]), float((*values)[2]));
    }
    std::optional<std::vector<double>> Numbers(const std::string& key) {
        const toml::node* node = Take(key);
        if (!node) return std::nullopt;
        const toml::array* array = node->as_array();
        if (!array) FailAt(key, "expected an array of numbers");
        std::vector<double> out;
        for (const toml::node& element : *array) {
            double v;
            if (auto i = element.value_exact<int64_t>()) v = double(*i);
            else if (auto d = element.value_exact<double>()) v = *d;
            else FailAt(key, "expected an array of numbers");
            if (!std::isfinite(v) || std::fabs(v) > 1e30) FailAt(key, "expected finite numbers");
            out.push_back(v);
        }
        return out;
    }
    const toml::table* Table(const std::string& key) {
        const toml::node* node = Take(key);
        if (!node) return nullptr;
        if (!node->is_table()) FailAt(key, "expected a table");
        return node->as_table();
    }
    // An array of tables ([[key]]); empty when absent.
    std::vector<const toml::table*> Tables(const std::string& key) {
        std::vector<const toml::table*> out;
        const toml::node* node = Take(key);
        if (!node) return out;
        const toml::array* array = node->as_array();
        if (!array) FailAt(key, "expected an array of tables ([[" + Key(key) + "]])");
        for (const toml::node& element : *array) {
            if (!element.is_table()) FailAt(key, "expected an array of tables ([[" + Key(key) + "]])");
            out.push_back(element.as_table());
        }
        return out;
    }
    const toml::node* Take(const std::string& key) {
        used_.insert(key);
        return table_.get(key);
    }
    // Rejects every key that no reader asked for.
    void Finish() const {
        for (const auto& [key, node] : table_) {
            std::string k(key.str());
            if (!used_.count(k))
                Fail("{}:{}: unknown key '{}'", file_, int(key.source().begin.line ? key.source().begin.line
                                                                                  : node.source().begin.line),
                     Key(k));
        }
    }
    const toml::table& table() const { return table_; }

private:
    const toml::table& table_;
    std::string where_;
    const std::string& file_;
    std::set<std::string> used_;
};

vec3 RequireVec3(TableReader& t, const std::string& key) {
    auto v = t.Vec3(key);
    if (!v) t.FailAt(key, "missing (required)");
    return *v;
}

vec3 RequireDirection(TableReader& t, const std::string& key, vec3 fallback) {
    auto v = t.Vec3(key);
    if (!v) return fallback;
    if (glm::dot(*v, *v) < 1e-12f) t.FailAt(key, "direction must not be zero");
    return glm::normalize(*v);
}

// rotate = [x, y, z] (Euler degrees, applied X then Y then Z) or { degrees = a, axis = [x, y, z] }.
std::optional<quat> ReadRotation(TableReader& t, const std::string& key) {
    const toml::node* node = t.table().get(key);
    if (!node) {
        t.Take(key);
        return std::nullopt;
    }
    if (node->is_table()) {
        TableReader r(*t.Table(key), t.Key(key), t.file());
        auto degrees = r.Number("degrees");
        auto axis = r.Vec3("axis");
        r.Finish();
        if (!degrees) r.FailAt("degrees", "missing (required)");
        if (!axis) r.FailAt("axis", "missing (required)");
        if (glm::dot(*axis, *axis) < 1e-12f) r.FailAt("axis", "must not be zero");
        return glm::angleAxis(Radians(float(*degrees)), glm::normalize(*axis));
    }
    auto euler = t.Numbers(key);
    if (euler->size() != 3) t.FailAt(key, "expected [x, y, z] Euler degrees or { degrees, axis }");
    quat qx = glm::angleAxis(Radians(float((*euler)[0])), vec3(1, 0, 0));
    quat qy = glm::angleAxis(Radians(float((*euler)[1])), vec3(0, 1, 0));
    quat qz = glm::angleAxis(Radians(float((*euler)[2])), vec3(0, 0, 1));
    return qz * qy * qx;
}

TransformKey ReadTransform(TableReader& t, const TransformKey& base) {
    TransformKey key = base;
    if (auto v = t.Vec3("translate")) key.pose.position = *v;
    if (auto q = ReadRotation(t, "rotate")) key.pose.orientation = *q;
    if (auto s = t.Vec3("scale", true)) {
        if (!IsFinite(*s) || std::min({s->x, s->y, s->z}) <= 0.0f) t.FailAt("scale", "scale must be > 0");
        key.scale = *s;
    }
    return key;
}

// Key lists must be sorted by time (strictly increasing).
template <typename Key>
void CheckKeyTimes(TableReader& t, const std::string& key, const std::vector<Key>& keys) {
    for (size_t i = 1; i < keys.size(); ++i)
        if (!(keys[i].time > keys[i - 1].time))
            t.FailAt(key, fmt::format("key times must increase (key {} has time {} after {})", i,
                                      keys[i].time, keys[i - 1].time));
}

Pose LookAtChecked(TableReader& t, const vec3& position, const vec3& target, const vec3& up) {
    vec3 forward = target - position;
    if (glm::dot(forward, forward) < 1e-12f) t.FailAt("target", "target equals position");
    if (glm::length(glm::cross(glm::normalize(forward), glm::normalize(up))) < 1e-4f)
        t.FailAt("up", "up is parallel to the view direction");
    return Pose::LookAt(position, target, up);
}

// Mitsuba's to_world (row-major 4x4): its camera looks down local +Z with +X to the image's
// left; ours looks down -Z with +X to the right, so right = -col0, up = col1, back = -col2.
Pose PoseFromMitsuba(TableReader& t, const std::vector<double>& m) {
    if (m.size() != 16) t.FailAt("mitsuba_to_world", "expected 16 numbers (row-major 4x4)");
    auto col = [&](int c) { return vec3(float(m[size_t(c)]), float(m[size_t(4 + c)]), float(m[size_t(8 + c)])); };
    vec3 forward = col(2), up = col(1), position = col(3);
    if (glm::length(forward) < 1e-6f || glm::length(up) < 1e-6f) t.FailAt("mitsuba_to_world", "degenerate matrix");
    return LookAtChecked(t, position, position + glm::normalize(forward), glm::normalize(up));
}

struct SceneFileLoader {
    const std::filesystem::path& path;
    std::string file;
    Scene& scene;
    LoadContext context;

    std::vector<MeshPart> LoadMeshFile(const std::filesystem::path& meshPath) {
        std::string key = meshPath.lexically_normal().string();
        if (auto it = context.meshFiles.find(key); it != context.meshFiles.end()) return it->second;
        std::string ext = meshPath.extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        std::vector<MeshPart> parts;
        if (ext == ".obj") parts = detail::LoadObj(meshPath, context);
        else if (ext == ".gltf" || ext == ".glb") parts = detail::LoadGltf(meshPath, context);
        else Fail("{}: unsupported mesh format '{}' (expected .obj, .gltf or .glb)", meshPath.string(), ext);
        context.meshFiles[key] = parts;
        return parts;
    }

    void AddInstances(const std::vector<MeshPart>& parts, const std::string& name,
                      const std::vector<TransformKey>& keys, bool loop) {
        for (const MeshPart& part : parts) {
            Instance instance;
            instance.name = part.name.empty() ? name : name + "/" + part.name;
            instance.mesh = part.mesh;
            instance.keys = keys;
            instance.loop = loop;
            scene.instances.push_back(std::move(instance));
        }
    }

    void ReadMesh(TableReader& t) {
        auto fileName = t.String("file");
        if (!fileName) t.FailAt("file", "missing (required)");
        std::filesystem::path meshPath = (path.parent_path() / *fileName).lexically_normal();
        std::string name = t.String("name").value_or(std::filesystem::path(*fileName).stem().string());
        TransformKey base = ReadTransform(t, TransformKey{});
        std::vector<TransformKey> keys;
        auto keyTables = t.Tables("keys");
        for (size_t i = 0; i < keyTables.size(); ++i) {
            TableReader k(*keyTables[i], t.Key(fmt::format("keys[{}]", i)), file);
            auto time = k.Number("time");
            if (!time) k.FailAt("time", "missing (required)");
            TransformKey key = ReadTransform(k, base);
            key.time = float(*time);
            k.Finish();
            keys.push_back(key);
        }
        CheckKeyTimes(t, "keys", keys);
        if (keys.empty()) keys.push_back(base);
        bool loop = t.Bool("loop").value_or(false);
        t.Finish();
        std::vector<MeshPart> parts;
        try {
            parts = LoadMeshFile(meshPath);
        } catch (const Error& e) {
            int line = int(t.table().source().begin.line);
            Fail("{}:{}: {}.file: {}", file, line, t.where(), e.what());
        }
        for (const Instance& instance : scene.instances)
            if (instance.name == name) t.FailAt("name", fmt::format("duplicate mesh name '{}'", name));
        AddInstances(parts, name, keys, loop);
    }

    void ReadLight(TableReader& t) {
        Light light;
        light.name = t.String("name").value_or(fmt::format("light{}", scene.lights.size()));
        std::string type = t.String("type").value_or("point");
        if (type == "point") light.type = LightType::Point;
        else if (type == "spot") light.type = LightType::Spot;
        else if (type == "directional") light.type = LightType::Directional;
        else t.FailAt("type", fmt::format("unknown light type '{}' (point, spot, directional)", type));
        light.color = t.Vec3("color", true).value_or(vec3(1.0f));
        if (std::min({light.color.x, light.color.y, light.color.z}) < 0.0f) t.FailAt("color", "must be >= 0");
        light.intensity = t.Float("intensity", 1.0f, 0.0f);
        light.position = t.Vec3("position").value_or(vec3(0.0f));
        light.direction = RequireDirection(t, "direction", vec3(0, -1, 0));
        if (auto target = t.Vec3("target")) {
            if (t.Has("direction")) t.FailAt("target", "give either direction or target");
            light.aimAtTarget = true;
            light.target = *target;
            if (light.type == LightType::Directional) {
                vec3 d = light.target - light.position;
                if (glm::dot(d, d) < 1e-12f) t.FailAt("target", "target equals position");
            }
        }
        float inner = t.Float("inner_degrees", 20.0f, 0.0f, 90.0f);
        float outer = t.Float("outer_degrees", std::max(30.0f, inner), 0.0f, 90.0f);
        if (outer < inner) t.FailAt("outer_degrees", "must be >= inner_degrees");
        light.spotInner = Radians(inner);
        light.spotOuter = Radians(outer);
        auto keyTables = t.Tables("keys");
        for (size_t i = 0; i < keyTables.size(); ++i) {
            TableReader k(*keyTables[i], t.Key(fmt::format("keys[{}]", i)), file);
            auto time = k.Number("time");
            if (!time) k.FailAt("time", "missing (required)");
            TransformKey key;
            key.time = float(*time);
            key.pose.position = RequireVec3(k, "position");
            k.Finish();
            light.path.push_back(key);
        }
        CheckKeyTimes(t, "keys", light.path);
        light.pathLoop = t.Bool("loop").value_or(false);
        if (const toml::table* sw = t.Table("switch")) {
            TableReader s(*sw, t.Key("switch"), file);
            ReadSchedule(s, light.switchPeriod, light.switchOnDuration, light.switchOffset);
            s.Finish();
        }
        t.Finish();
        scene.lights.push_back(light);
    }

    void ReadSchedule(TableReader& s, float& period, float& on, float& offset) {
        period = s.Float("period", 0.0f, 0.0f);
        if (!s.Has("period")) s.FailAt("period", "missing (required)");
        on = s.Float("on", 0.5f * period, 0.0f);
        offset = s.Float("offset", 0.0f);
        if (period <= 0.0f) s.FailAt("period", "must be > 0");
        if (on > period) s.FailAt("on", "on-duration exceeds the period");
    }

    void ReadEmissionSwitch(TableReader& t) {
        auto name = t.String("instance");
        if (!name) t.FailAt("instance", "missing (required)");
        Scene::EmissionSwitch sw{};
        ReadSchedule(t, sw.period, sw.onDuration, sw.offset);
        t.Finish();
        bool found = false;
        for (size_t i = 0; i < scene.instances.size(); ++i) {
            const std::string& n = scene.instances[i].name;
            if (n == *name || n.rfind(*name + "/", 0) == 0) {
                sw.instance = uint32_t(i);
                scene.emissionSwitches.push_back(sw);
                found = true;
            }
        }
        if (!found) t.FailAt("instance", fmt::format("unknown instance '{}'", *name));
    }

    void ReadMaterialOverride(TableReader& t) {
        auto name = t.String("name");
        if (!name) t.FailAt("name", "missing (required)");
        std::vector<Material*> targets;
        for (Material& m : scene.materials)
            if (m.name == *name) targets.push_back(&m);
        if (targets.empty()) {
            std::string known;
            for (const Material& m : scene.materials) known += (known.empty() ? "" : ", ") + m.name;
            t.FailAt("name", fmt::format("unknown material '{}' (known: {})", *name, known));
        }
        auto baseColor = t.Vec3("base_color", true);
        float roughness = t.Float("roughness", -1.0f, 0.0f, 1.0f);
        float metallic = t.Float("metallic", -1.0f, 0.0f, 1.0f);
        float specular = t.Float("specular", -1.0f, 0.0f, 1.0f);
        auto emission = t.Vec3("emission", true);
        auto twoSided = t.Bool("emission_two_sided");
        int texture = -1;
        if (auto tex = t.String("base_color_texture"))
            texture = detail::LoadTextureFile(path.parent_path() / *tex, true,
                                              fmt::format("{}: {}", file, t.Key("base_color_texture")), context);
        const int roughnessMap = ReadScalarMap(t, "roughness_texture");
        const int metallicMap = ReadScalarMap(t, "metallic_texture");
        for (const auto& [key, colour] : {std::pair{"base_color", baseColor}, std::pair{"emission", emission}}) {
            if (!colour) continue;
            std::string problem = detail::MaterialColourProblem({colour->x, colour->y, colour->z});
            if (!problem.empty()) t.FailAt(key, problem);
        }
        t.Finish();
        for (Material* m : targets) {
            if (baseColor) m->baseColor = *baseColor;
            if (t.Has("roughness")) m->roughness = roughness;
            if (t.Has("metallic")) m->metallic = metallic;
            if (t.Has("specular")) m->specular = specular;
            if (emission) m->emission = *emission;
            if (twoSided) m->emissionTwoSided = *twoSided;
            if (texture >= 0) m->baseColorTexture = texture;
            if (roughnessMap >= 0) m->roughnessTexture = roughnessMap;
            if (metallicMap >= 0) m->metallicTexture = metallicMap;
        }
    }

    // A roughness / metallic map: an image file (linear, R channel) or a procedural pattern
    // { pattern = "checker" | "cells", cells = [x, y], values = [a, b], texels_per_cell = 4 }
    // ("cells": each cell a or b by a hash of its coordinates, a binary texture like text).
    // Returns the texture index, or -1 when the key is absent.
    int ReadScalarMap(TableReader& t, const std::string& key) {
        if (!t.Has(key)) return -1;
        if (t.table().get(key)->is_string())
            return detail::LoadTextureFile(path.parent_path() / *t.String(key), false,
                                           fmt::format("{}: {}", file, t.Key(key)), context);
        const toml::table* spec = t.Table(key);
        if (!spec) t.FailAt(key, "expected a file name or { pattern = ..., cells = [x, y], values = [a, b] }");
        TableReader p(*spec, t.Key(key), file);
        const std::string pattern = p.String("pattern").value_or("checker");
        if (pattern != "checker" && pattern != "cells")
            p.FailAt("pattern", fmt::format("unknown pattern '{}' (known: checker, cells)", pattern));
        auto cells = p.Numbers("cells");
        if (!cells || cells->size() != 2 || (*cells)[0] < 1 || (*cells)[1] < 1 || (*cells)[0] > 4096 ||
            (*cells)[1] > 4096)
            p.FailAt("cells", "expected [x, y] cell counts in [1, 4096]");
        auto values = p.Numbers("values");
        if (!values || values->size() != 2 || std::min((*values)[0], (*values)[1]) < 0.0 ||
            std::max((*values)[0], (*values)[1]) > 1.0)
            p.FailAt("values", "expected [a, b] in [0, 1]");
        const int perCell = int(p.Float("texels_per_cell", 4.0f, 1.0f, 64.0f));
        p.Finish();
        context.scene.textures.push_back(detail::PatternTexture(
            fmt::format("{}:{}", file, t.Key(key)), pattern == "cells", int((*cells)[0]), int((*cells)[1]),
            float((*values)[0]), float((*values)[1]), perCell));
        return int(context.scene.textures.size()) - 1;
    }

    void ReadCameraKeys(TableReader& camera, const std::vector<const toml::table*>& keys) {
        for (size_t i = 0; i < keys.size(); ++i) {
            TableReader k(*keys[i], camera.Key(fmt::format("keys[{}]", i)), file);
            auto time = k.Number("time");
            if (!time) k.FailAt("time", "missing (required)");
            vec3 position = RequireVec3(k, "position"), target = RequireVec3(k, "target");
            vec3 up = k.Vec3("up").value_or(vec3(0, 1, 0));
            scene.cameraPath.push_back(CameraKey{float(*time), LookAtChecked(k, position, target, up)});
            k.Finish();
        }
        CheckKeyTimes(camera, "keys", scene.cameraPath);
    }

    void Load() {
        toml::table root;
        try {
            root = toml::parse_file(file);
        } catch (const toml::parse_error& e) {
            Fail("{}:{}: {}", file, int(e.source().begin.line), std::string(e.description()));
        }
        TableReader t(root, "", file);
        scene.name = t.String("name").value_or(path.stem().string());
        scene.frameRate = t.Float("frame_rate", 30.0f, 1e-3f, 1e4f);
        scene.background = t.Vec3("background", true).value_or(vec3(0.0f));
        if (std::min({scene.background.x, scene.background.y, scene.background.z}) < 0.0f)
            t.FailAt("background", "must be >= 0");
        scene.horizontalFovDegrees = t.Float("fov", 60.0f, 1.0f, 179.0f);
        auto meshes = t.Tables("mesh");
        if (meshes.empty()) t.FailAt("mesh", "a scene needs at least one [[mesh]]");
        for (size_t i = 0; i < meshes.size(); ++i) {
            TableReader m(*meshes[i], fmt::format("mesh[{}]", i), file);
            ReadMesh(m);
        }
        for (const toml::table* m : t.Tables("material")) {
            TableReader r(*m, "material", file);
            ReadMaterialOverride(r);
        }
        auto lights = t.Tables("light");
        for (size_t i = 0; i < lights.size(); ++i) {
            TableReader l(*lights[i], fmt::format("light[{}]", i), file);
            ReadLight(l);
        }
        auto switches = t.Tables("emission_switch");
        for (size_t i = 0; i < switches.size(); ++i) {
            TableReader s(*switches[i], fmt::format("emission_switch[{}]", i), file);
            ReadEmissionSwitch(s);
        }
        if (const toml::table* camera = t.Table("camera")) {
            TableReader c(*camera, "camera", file);
            auto keys = c.Tables("keys");
            bool hasStatic = c.Has("position") || c.Has("target");
            bool hasMitsuba = c.Has("mitsuba_to_world");
            if (int(hasStatic) + int(hasMitsuba) + int(!keys.empty()) != 1)
                c.FailAt(keys.empty() ? "position" : "keys",
                         "give exactly one of position + target, mitsuba_to_world or [[camera.keys]]");
            scene.cameraLoop = c.Bool("loop").value_or(false);
            if (hasMitsuba) {
                scene.cameraPath = {CameraKey{0.0f, PoseFromMitsuba(c, *c.Numbers("mitsuba_to_world"))}};
            } else if (hasStatic) {
                vec3 position = RequireVec3(c, "position"), target = RequireVec3(c, "target");
                vec3 up = c.Vec3("up").value_or(vec3(0, 1, 0));
                scene.cameraPath = {CameraKey{0.0f, LookAtChecked(c, position, target, up)}};
            } else {
                ReadCameraKeys(c, keys);
            }
            c.Finish();
        }
        t.Finish();
    }
};

// A camera on +Z of the bounding box centre (at time 0) that sees the whole box.
void FrameBoundingBox(Scene& scene) {
    vec3 lo(1e30f), hi(-1e30f);
    SceneState state = scene.StateAt(0.0f);
    for (size_t i = 0; i < scene.instances.size(); ++i)
        for (const vec3& p : scene.meshes[scene.instances[i].mesh].positions) {
            vec3 w = vec3(state.worldFromObject[i] * vec4(p, 1.0f));
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
    vec3 centre = 0.5f * (lo + hi);
    float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
    // Fit the bounding sphere into the vertical FOV of a 16:9 image with the horizontal FOV.
    float tanHalf = std::tan(0.5f * Radians(scene.horizontalFovDegrees)) / (16.0f / 9.0f);
    float distance = radius / std::sin(std::atan(tanHalf));
    scene.cameraPath = {CameraKey{0.0f, Pose::LookAt(centre + vec3(0, 0, distance), centre)}};
}

}  // namespace

Scene LoadScene(const std::filesystem::path& path) {
    Scene scene;
    scene.sourcePath = path;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) Fail("{}: scene file not found", path.string());
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    SceneFileLoader loader{path, path.string(), scene, LoadContext{scene, {}, {}}};
    if (ext == ".toml") loader.context.Read(path);  // a bare mesh is recorded by its loader
    try {
        if (ext == ".toml") {
            loader.Load();
        } else if (ext == ".obj" || ext == ".gltf" || ext == ".glb") {
            // A bare mesh: one static instance, default camera, and a white sky unless it emits.
            scene.name = path.stem().string();
            loader.AddInstances(loader.LoadMeshFile(path), scene.name, {}, false);
            if (CountEmissiveTriangles(scene) == 0) scene.background = vec3(1.0f);
        } else {
            Fail("{}: unknown scene file type '{}' (expected .toml, .obj, .gltf or .glb)", path.string(), ext);
        }
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        // Third-party parsers may throw (bad_alloc on absurd sizes, out_of_range): keep one line.
        Fail("{}: cannot load scene: {}", path.string(), e.what());
    }
    if (scene.cameraPath.empty()) FrameBoundingBox(scene);
    return scene;
}

}  // namespace fovrt
