#include "pipeline/reference_cache.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "core/content_hash.h"
#include "core/error.h"
#include "core/rng.h"
#include "io/exr.h"
#include "scene/scene_serialize.h"

namespace fovrt {

uint64_t SceneFingerprint(const Scene& scene) {
    ContentHash h;
    SerializeScene(scene, [&](const void* data, size_t size) { h.Bytes(data, size); });
    return h.Digest();
}

std::map<std::string, std::string> SceneFileHashes(const Scene& scene) {
    std::map<std::string, std::string> hashes;
    const std::filesystem::path base = scene.sourcePath.parent_path().empty() ? "." : scene.sourcePath.parent_path();
    for (const std::filesystem::path& file : scene.files) {
        std::ifstream in(file, std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        const std::filesystem::path relative = file.lexically_relative(base);
        hashes[(relative.empty() ? file : relative).generic_string()] = in ? HashHex(bytes.str()) : "unreadable";
    }
    return hashes;
}

ReferenceKey MakeReferenceKey(const Scene& scene, uint64_t fingerprint, uint32_t frame,
                              double timeSeconds, int eye, const EyeCamera& camera, int spp,
                              int maxDepth, uint32_t seed) {
    bool timeless = IsStaticScene(scene);
    return ReferenceKey{fingerprint, timeless ? 0u : frame, timeless ? 0.0 : timeSeconds, eye,
                        camera, spp, maxDepth, seed};
}

std::string ReferenceKey::Hex() const {
    ContentHash h;
    // v3: sampled with the key's seed and frame, not the run's; v4: area lights one-sided by default.
    h.String("fovrt-reference-v4");
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
    // The mean of chunks is another image than one render of as many samples.
    if (ReferenceChunks(spp) > 1) h.String(fmt::format("chunks of {}", kReferenceChunkSpp));
    return h.Hex();
}

ReferenceKey ReferenceKey::Chunk(int k) const {
    ReferenceKey chunk = *this;
    chunk.spp = kReferenceChunkSpp;
    chunk.seed = k == 0 ? seed : HashCombine(seed, uint32_t(k));
    return chunk;
}

std::filesystem::path ReferenceCache::PathOf(const ReferenceKey& key) const {
    return dir_ / fmt::format("f{:05d}-e{}-{}spp-{}.exr", key.frame, key.eye, key.spp, key.Hex());
}

namespace {

// Every entry carries the key it was rendered for and a checksum of its pixels (EXR header
// attributes), so an entry copied over another's file, edited or damaged is never used.
constexpr const char* kKeyAttribute = "fovrt.reference_key";
constexpr const char* kChecksumAttribute = "fovrt.pixel_checksum";

std::string PixelChecksum(const Plane<vec3>& image) {
    ContentHash h;
    h.Bytes(image.data(), image.size() * sizeof(vec3));
    return h.Hex();
}

void WriteEntry(const std::filesystem::path& path, const std::string& hex, const Plane<vec3>& image) {
    ExrAttributes attributes;
    attributes.strings[kKeyAttribute] = hex;
    attributes.strings[kChecksumAttribute] = PixelChecksum(image);
    WriteExrLayers(path, image.width(), image.height(), {ExrLayer::FromPlane("", image)}, attributes);
}

// The entry's image, or the reason it cannot be trusted.
struct LoadedEntry {
    Plane<vec3> image;
    std::string problem;
};

LoadedEntry ReadEntry(const std::filesystem::path& path, const std::string& hex) {
    LoadedEntry entry;
    try {
        const ExrImage exr = ReadExr(path);
        const auto& strings = exr.attributes.strings;
        const auto key = strings.find(kKeyAttribute), checksum = strings.find(kChecksumAttribute);
        if (key == strings.end() || checksum == strings.end()) {
            entry.problem = "has no key and checksum (written by an older fovrt)";
            return entry;
        }
        if (key->second != hex) {
            entry.problem = fmt::format("holds the entry of key {}, not {}", key->second, hex);
            return entry;
        }
        entry.image = Plane<vec3>(exr.width, exr.height);
        const auto &r = exr.Floats("R"), &g = exr.Floats("G"), &b = exr.Floats("B");
        for (size_t i = 0; i < entry.image.size(); ++i) entry.image[i] = vec3(r[i], g[i], b[i]);
        if (PixelChecksum(entry.image) != checksum->second)
            entry.problem = "pixel checksum mismatch (the file changed after it was written)";
    } catch (const Error& e) {
        entry.problem = fmt::format("unreadable ({})", e.what());
    }
    return entry;
}

}  // namespace

std::optional<Plane<vec3>> ReferenceCache::Load(const ReferenceKey& key, const char* remedy) {
    const std::string hex = key.Hex();
    for (const auto& [recentHex, image] : recent_)
        if (recentHex == hex) return image;
    const std::filesystem::path path = PathOf(key);
    if (!std::filesystem::exists(path)) return std::nullopt;
    LoadedEntry entry = ReadEntry(path, hex);
    if (!entry.problem.empty()) {
        std::fprintf(stderr, "fovrt: reference cache entry %s %s; %s\n", path.c_str(), entry.problem.c_str(), remedy);
        return std::nullopt;
    }
    Remember(hex, std::move(entry.image));
    return recent_.back().second;
}

std::optional<Plane<vec3>> ReferenceCache::Find(const ReferenceKey& key) {
    return Load(key, fmt::format("ignored (remove it: rm '{}')", PathOf(key).string()).c_str());
}

Plane<vec3> ReferenceCache::GetOrRender(const ReferenceKey& key, Renderer& renderer, bool* hit) {
    if (std::optional<Plane<vec3>> cached = Load(key, "rendering it again")) {
        if (hit) *hit = true;
        return std::move(*cached);
    }
    if (hit) *hit = false;
    Plane<vec3> image;
    if (const int chunks = ReferenceChunks(key.spp); chunks > 1) {
        for (int k = 0; k < chunks; ++k) {
            const Plane<vec3> chunk = GetOrRender(key.Chunk(k), renderer);
            if (k == 0) image = Plane<vec3>(chunk.width(), chunk.height());
            for (size_t i = 0; i < image.size(); ++i) image[i] += chunk[i];
        }
        for (size_t i = 0; i < image.size(); ++i) image[i] *= 1.0f / float(chunks);
    } else {
        renderer.RenderReference(key.eye, key.camera, key.spp, HashCombine(key.seed, key.frame), image);
    }
    WriteEntry(PathOf(key), key.Hex(), image);
    Remember(key.Hex(), image);
    return image;
}

void ReferenceCache::Remember(const std::string& hex, Plane<vec3> image) {
    if (recent_.size() == kInMemoryEntries) recent_.erase(recent_.begin());
    recent_.emplace_back(hex, std::move(image));
}

}  // namespace fovrt
