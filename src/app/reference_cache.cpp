#include "app/reference_cache.h"

#include <cstring>

#include <fmt/format.h>

#include "io/exr.h"

namespace fovrt {
namespace {

// FNV-1a, 64 bit: stable across runs and platforms (unlike std::hash).
class Fnv1a {
public:
    void Bytes(const void* data, size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < size; ++i) {
            hash_ ^= p[i];
            hash_ *= 1099511628211ull;
        }
    }
    template <typename T>
    void Value(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        Bytes(&v, sizeof(T));
    }
    template <typename T>
    void Vector(const std::vector<T>& v) {
        Value(v.size());
        if (!v.empty()) Bytes(v.data(), v.size() * sizeof(T));
    }
    void String(const std::string& s) {
        Value(s.size());
        Bytes(s.data(), s.size());
    }
    uint64_t Digest() const { return hash_; }

private:
    uint64_t hash_ = 1469598103934665603ull;
};

void HashKeys(Fnv1a& h, const std::vector<TransformKey>& keys) {
    for (const TransformKey& k : keys) {
        h.Value(k.time);
        h.Value(k.pose.orientation);
        h.Value(k.pose.position);
        h.Value(k.scale);
    }
}

}  // namespace

uint64_t SceneFingerprint(const Scene& scene) {
    Fnv1a h;
    for (const Mesh& mesh : scene.meshes) {
        h.Vector(mesh.positions);
        h.Vector(mesh.normals);
        h.Vector(mesh.uvs);
        h.Vector(mesh.triangles);
        h.Vector(mesh.materials);
    }
    for (const Material& m : scene.materials) {
        h.Value(m.baseColor);
        h.Value(m.baseColorTexture);
        h.Value(m.roughness);
        h.Value(m.metallic);
        h.Value(m.metallicRoughnessTexture);
        h.Value(m.specular);
        h.Value(m.emission);
    }
    for (const Texture& t : scene.textures) h.Vector(t.texels);
    for (const Instance& instance : scene.instances) {
        h.Value(instance.mesh);
        h.Value(instance.loop);
        HashKeys(h, instance.keys);
    }
    for (const Light& light : scene.lights) {
        h.Value(light.type);
        h.Value(light.color);
        h.Value(light.intensity);
        h.Value(light.position);
        h.Value(light.direction);
        h.Value(light.spotInner);
        h.Value(light.spotOuter);
        HashKeys(h, light.path);
        h.Value(light.pathLoop);
        h.Value(light.aimAtTarget);
        h.Value(light.target);
        h.Value(light.switchPeriod);
        h.Value(light.switchOnDuration);
        h.Value(light.switchOffset);
    }
    for (const Scene::EmissionSwitch& s : scene.emissionSwitches) h.Value(s);
    h.Value(scene.background);
    return h.Digest();
}

ReferenceKey MakeReferenceKey(const Scene& scene, uint64_t fingerprint, uint32_t frame,
                              double timeSeconds, int eye, const EyeCamera& camera, int spp,
                              int maxDepth, uint32_t seed) {
    bool timeless = IsStaticScene(scene);
    return ReferenceKey{fingerprint, timeless ? 0u : frame, timeless ? 0.0 : timeSeconds, eye,
                        camera, spp, maxDepth, seed};
}

std::string ReferenceKey::Hex() const {
    Fnv1a h;
    h.String("fovrt-reference-v1");
    h.Value(sceneFingerprint);
    h.Value(frame);
    h.Value(timeSeconds);
    h.Value(eye);
    h.Value(camera.pose().orientation);
    h.Value(camera.pose().position);
    h.Value(camera.fov());
    h.Value(camera.width());
    h.Value(camera.height());
    h.Value(spp);
    h.Value(maxDepth);
    h.Value(seed);
    return fmt::format("{:016x}", h.Digest());
}

std::filesystem::path ReferenceCache::PathOf(const ReferenceKey& key) const {
    return dir_ / fmt::format("f{:05d}-e{}-{}spp-{}.exr", key.frame, key.eye, key.spp, key.Hex());
}

Plane<vec3> ReferenceCache::GetOrRender(const ReferenceKey& key, Renderer& renderer, bool* hit) {
    const std::string hex = key.Hex();
    for (const auto& [recentHex, image] : recent_)
        if (recentHex == hex) {
            if (hit) *hit = true;
            return image;
        }
    std::filesystem::path path = PathOf(key);
    Plane<vec3> image;
    if (std::filesystem::exists(path)) {
        if (hit) *hit = true;
        image = ReadRgbExr(path);
    } else {
        if (hit) *hit = false;
        renderer.RenderReference(key.eye, key.camera, key.spp, image);
        WriteRgbExr(path, image);
    }
    if (recent_.size() == kInMemoryEntries) recent_.erase(recent_.begin());
    recent_.emplace_back(hex, image);
    return image;
}

}  // namespace fovrt
