// ReferenceCache: high-spp ground-truth frames on disk, keyed by everything that changes them
// (scene content, frame time, eye camera, resolution, spp, path length, reference seed), so
// repeated experiments never re-render a reference. Entries are RGB EXRs written atomically. The
// image is sampled with HashCombine(seed, frame) of the key (frame 0 for a static scene), so it
// is a function of the key alone: which frame rendered it first, and the run seed, do not matter.
// Each entry carries its key and a checksum of its pixels; an entry that fails either check (copied
// over another's file, edited, damaged, or written before entries carried them) is never used: one
// line on stderr names the file, and GetOrRender renders it again.
//
// A reference of more than kReferenceChunkSpp samples per pixel, a multiple of it, is the mean of
// chunks of kReferenceChunkSpp samples, each an entry of its own: chunk 0 is the reference of that
// many samples with the same seed, chunk k > 0 the one seeded HashCombine(seed, k). Raising
// reference.spp from 1024 to 4096 renders three chunks and reuses the 1024-spp entry, and a long
// render that is interrupted keeps the chunks it finished.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace fovrt {

// A content fingerprint of a scene: the hash of SerializeScene's stream (scene/scene_serialize.h),
// so everything that can change the image is in it.
uint64_t SceneFingerprint(const Scene& scene);
// The content hash (ContentHash, hex) of each file the scene loaded (Scene::files), by its path
// relative to the scene file's folder (so a copy of the scene elsewhere, another machine's
// checkout, gives the same map), naming what changed between two loads file by file;
// "unreadable" for a file gone since.
std::map<std::string, std::string> SceneFileHashes(const Scene& scene);

inline constexpr int kReferenceChunkSpp = 1024;
// How many chunks a reference of `spp` samples is rendered in (1: in one piece).
inline int ReferenceChunks(int spp) {
    return spp > kReferenceChunkSpp && spp % kReferenceChunkSpp == 0 ? spp / kReferenceChunkSpp : 1;
}

struct ReferenceKey {
    uint64_t sceneFingerprint = 0;
    uint32_t frame = 0;
    double timeSeconds = 0.0;
    int eye = 0;
    EyeCamera camera;
    int spp = 0;
    int maxDepth = 0;
    uint32_t seed = 0;  // reference.seed (never the run seed: every run seed shares the reference)

    std::string Hex() const;  // the file stem of the cache entry
    ReferenceKey Chunk(int k) const;  // chunk k of a reference rendered in chunks
};

// The key of one reference frame. For a static scene the frame and time are left out, so every
// frame seen from the same eye pose shares one reference (e.g. Veach Ajar's fixed camera).
ReferenceKey MakeReferenceKey(const Scene& scene, uint64_t fingerprint, uint32_t frame,
                              double timeSeconds, int eye, const EyeCamera& camera, int spp,
                              int maxDepth, uint32_t seed);

class ReferenceCache {
public:
    explicit ReferenceCache(std::filesystem::path dir) : dir_(std::move(dir)) {}

    std::filesystem::path PathOf(const ReferenceKey& key) const;
    // Returns the cached image, or renders it with `renderer` (already at the key's frame) and
    // stores it. `hit` (optional) says which happened. The most recent entries also stay in
    // memory, so a static scene's reference is read from disk once per eye, not once per frame.
    Plane<vec3> GetOrRender(const ReferenceKey& key, Renderer& renderer, bool* hit = nullptr);
    // The cached image, or nullopt when none was rendered yet (never renders: a live session
    // shows its error view only where `fovrt reference` or an experiment left a reference).
    std::optional<Plane<vec3>> Find(const ReferenceKey& key);

private:
    // The verified entry (memory first, then disk); a bad one is reported with `remedy` and skipped.
    std::optional<Plane<vec3>> Load(const ReferenceKey& key, const char* remedy);
    void Remember(const std::string& hex, Plane<vec3> image);

    static constexpr size_t kInMemoryEntries = 2;  // one per eye
    std::filesystem::path dir_;
    std::vector<std::pair<std::string, Plane<vec3>>> recent_;  // most recent last
};

}  // namespace fovrt
