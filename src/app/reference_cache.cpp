#include "app/reference_cache.h"

#include <cstring>

#include <fmt/format.h>

#include "core/rng.h"
#include "io/exr.h"
#include "scene/scene_serialize.h"

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
    void String(const std::string& s) {
        Value(s.size());
        Bytes(s.data(), s.size());
    }
    uint64_t Digest() const { return hash_; }

private:
    uint64_t hash_ = 1469598103934665603ull;
};

}  // namespace

uint64_t SceneFingerprint(const Scene& scene) {
    Fnv1a h;
    SerializeScene(scene, [&](const void* data, size_t size) { h.Bytes(data, size); });
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
    h.String("fovrt-reference-v3");  // v3: sampled with the key's seed and frame, not the run's
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

std::optional<Plane<vec3>> ReferenceCache::Find(const ReferenceKey& key) {
    const std::string hex = key.Hex();
    for (const auto& [recentHex, image] : recent_)
        if (recentHex == hex) return image;
    const std::filesystem::path path = PathOf(key);
    if (!std::filesystem::exists(path)) return std::nullopt;
    Remember(hex, ReadRgbExr(path));
    return recent_.back().second;
}

Plane<vec3> ReferenceCache::GetOrRender(const ReferenceKey& key, Renderer& renderer, bool* hit) {
    if (std::optional<Plane<vec3>> cached = Find(key)) {
        if (hit) *hit = true;
        return std::move(*cached);
    }
    if (hit) *hit = false;
    Plane<vec3> image;
    renderer.RenderReference(key.eye, key.camera, key.spp, HashCombine(key.seed, key.frame), image);
    WriteRgbExr(PathOf(key), image);
    Remember(key.Hex(), image);
    return image;
}

void ReferenceCache::Remember(const std::string& hex, Plane<vec3> image) {
    if (recent_.size() == kInMemoryEntries) recent_.erase(recent_.begin());
    recent_.emplace_back(hex, std::move(image));
}

}  // namespace fovrt
