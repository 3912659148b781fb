// Reference cache: keys change with everything that changes the image and nothing else, and a
// cached entry reads back exactly what was rendered.
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/reference_cache.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace fovrt;

namespace {

EyeCamera Camera(float x = 0.0f) {
    return EyeCamera(Pose::LookAt(vec3(x, 1, 4), vec3(0, 1, 0)), Fov::FromHorizontal(1.0f, 1.5f),
                     24, 16);
}

}  // namespace

TEST_CASE("reference keys: static scenes share one reference per eye pose", "[app]") {
    Scene scene = LoadScene(ResolveSceneName("cornell"));
    REQUIRE(IsStaticScene(scene));
    uint64_t fp = SceneFingerprint(scene);
    auto a = MakeReferenceKey(scene, fp, 3, 0.1, 0, Camera(), 64, 2, 1);
    auto b = MakeReferenceKey(scene, fp, 9, 0.3, 0, Camera(), 64, 2, 1);
    CHECK(a.Hex() == b.Hex());
    CHECK(a.Hex() != MakeReferenceKey(scene, fp, 3, 0.1, 1, Camera(), 64, 2, 1).Hex());      // eye
    CHECK(a.Hex() != MakeReferenceKey(scene, fp, 3, 0.1, 0, Camera(0.1f), 64, 2, 1).Hex());  // pose
    CHECK(a.Hex() != MakeReferenceKey(scene, fp, 3, 0.1, 0, Camera(), 128, 2, 1).Hex());     // spp
    CHECK(a.Hex() != MakeReferenceKey(scene, fp, 3, 0.1, 0, Camera(), 64, 3, 1).Hex());      // depth
}

TEST_CASE("reference keys: animated scenes key on time, content changes the fingerprint", "[app]") {
    Scene pillars = LoadScene(ResolveSceneName("pillars"));
    REQUIRE_FALSE(IsStaticScene(pillars));
    uint64_t fp = SceneFingerprint(pillars);
    CHECK(MakeReferenceKey(pillars, fp, 3, 0.1, 0, Camera(), 64, 2, 1).Hex() !=
          MakeReferenceKey(pillars, fp, 9, 0.3, 0, Camera(), 64, 2, 1).Hex());
    Scene changed = pillars;
    changed.materials[0].baseColor.r += 0.01f;
    CHECK(SceneFingerprint(changed) != fp);
}

namespace {

// A scene with at least one of everything the key must see (room has textures and meshes; a light
// and a second camera key are added when the file has none).
Scene EverythingScene() {
    Scene scene = LoadScene(ResolveSceneName("room"));
    if (scene.lights.empty()) scene.lights.push_back(Light{});
    if (scene.textures.empty()) scene.textures.push_back(Texture{"t", 1, 1, {vec4(0.5f)}});
    if (scene.cameraPath.size() < 2) scene.cameraPath.push_back({1.0f, Pose::LookAt(vec3(1, 1, 1), vec3(0))});
    if (scene.instances.empty() || scene.instances[0].keys.empty())
        FAIL("room needs an instance with a transform key");
    return scene;
}

std::string KeyOf(const Scene& scene) {
    return MakeReferenceKey(scene, SceneFingerprint(scene), 0, 0.0, 0, Camera(), 64, 2, 1).Hex();
}

}  // namespace

TEST_CASE("reference keys: identical scenes give identical keys, any content change a new key", "[app]") {
    const Scene base = EverythingScene();
    const std::string key = KeyOf(base);
    CHECK(KeyOf(EverythingScene()) == key);  // loaded twice: same stream
    Scene renamed = base;                    // names and paths never change an image
    renamed.name = "elsewhere";
    renamed.sourcePath = "/elsewhere.toml";
    renamed.materials[0].name += "-renamed";
    CHECK(KeyOf(renamed) == key);

    const std::vector<std::pair<const char*, std::function<void(Scene&)>>> changes = {
        {"a vertex", [](Scene& s) { s.meshes[0].positions[0].x += 1e-3f; }},
        {"a normal", [](Scene& s) { s.meshes[0].normals.push_back(vec3(0, 1, 0)); }},
        {"a triangle's material", [](Scene& s) { s.meshes[0].materials[0] ^= 1u; }},
        {"a base colour", [](Scene& s) { s.materials[0].baseColor.g += 1e-3f; }},
        {"a roughness", [](Scene& s) { s.materials.back().roughness *= 0.5f; }},
        {"an emission", [](Scene& s) { s.materials[0].emission.r += 1.0f; }},
        {"an emission's sides", [](Scene& s) { s.materials[0].emissionTwoSided = !s.materials[0].emissionTwoSided; }},
        {"a texture binding", [](Scene& s) { s.materials[0].baseColorTexture = s.materials[0].baseColorTexture == 0 ? -1 : 0; }},
        {"a texel", [](Scene& s) { s.textures[0].texels.back().b += 1e-3f; }},
        {"a texture's shape", [](Scene& s) { std::swap(s.textures[0].width, s.textures[0].height);
                                             s.textures[0].width += 1; }},
        {"a light's intensity", [](Scene& s) { s.lights[0].intensity *= 2.0f; }},
        {"a light's switching", [](Scene& s) { s.lights[0].switchOffset += 0.25f; }},
        {"a light's path", [](Scene& s) { s.lights[0].path.push_back(TransformKey{}); }},
        {"an instance key", [](Scene& s) { s.instances[0].keys[0].pose.position.y += 1e-3f; }},
        {"an instance loop", [](Scene& s) { s.instances[0].loop = !s.instances[0].loop; }},
        {"an emission switch", [](Scene& s) { s.emissionSwitches.push_back({0, 1.0f, 0.5f, 0.0f}); }},
        {"a camera keyframe", [](Scene& s) { s.cameraPath.back().pose.orientation.x += 1e-3f; }},
        {"the camera loop", [](Scene& s) { s.cameraLoop = !s.cameraLoop; }},
        {"the frame rate", [](Scene& s) { s.frameRate = 90.0f; }},
        {"the background", [](Scene& s) { s.background = vec3(0.1f); }},
    };
    for (const auto& [what, change] : changes) {
        Scene changed = base;
        change(changed);
        CAPTURE(what);
        CHECK(KeyOf(changed) != key);
    }
}

TEST_CASE("scene file hashes: every file the scene loaded, once; an MTL edit names that file alone", "[app]") {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / "fovrt-scene-file-hashes";
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const char* file : {"cornell.toml", "cornell_room.obj", "cornell_room.mtl", "cube.obj", "cube.mtl"})
        fs::copy_file(test::SourceDir() / "scenes" / file, dir / file);
    const Scene before = LoadScene(dir / "cornell.toml");
    const std::map<std::string, std::string> hashes = SceneFileHashes(before);
    std::vector<std::string> names;
    for (const fs::path& file : before.files) names.push_back(file.filename().string());
    // The cube, instanced twice, read once.
    CHECK(names == std::vector<std::string>{"cornell.toml", "cornell_room.obj", "cornell_room.mtl", "cube.obj", "cube.mtl"});
    CHECK(hashes.size() == 5);
    CHECK(hashes.count("cornell_room.mtl") == 1);  // by its path beside the scene file
    // The same scene in another folder (another machine's checkout): the same map.
    fs::copy(dir, dir / "elsewhere");
    CHECK(SceneFileHashes(LoadScene(dir / "elsewhere" / "cornell.toml")) == hashes);

    std::string mtl = test::ReadFile(dir / "cornell_room.mtl");
    const size_t kd = mtl.find("Kd ");
    REQUIRE(kd != std::string::npos);
    mtl.replace(kd, mtl.find('\n', kd) - kd, "Kd 0.9 0.2 0.2");  // one Kd line edited
    std::ofstream(dir / "cornell_room.mtl", std::ios::binary) << mtl;
    const Scene after = LoadScene(dir / "cornell.toml");
    CHECK(SceneFingerprint(after) != SceneFingerprint(before));
    std::vector<std::string> changed;
    for (const auto& [file, hash] : SceneFileHashes(after))
        if (hashes.at(file) != hash) changed.push_back(fs::path(file).filename().string());
    CHECK(changed == std::vector<std::string>{"cornell_room.mtl"});
    fs::remove_all(dir);
}

// Cornell's renderer at frame 0 and an empty cache folder, removed again at the end.
struct CornellCacheBench {
    Scene scene = LoadScene(ResolveSceneName("cornell"));
    std::unique_ptr<Renderer> renderer = CreateRenderer(scene, RenderSettings{});
    std::filesystem::path dir;

    explicit CornellCacheBench(const std::string& name) : dir(std::filesystem::temp_directory_path() / name) {
        renderer->SetFrame(0);
        std::filesystem::remove_all(dir);
    }
    ~CornellCacheBench() { std::filesystem::remove_all(dir); }
};

TEST_CASE("reference cache renders once, then reads back the same pixels", "[app]") {
    CornellCacheBench bench("fovrt_reference_cache_test");
    const Scene& scene = bench.scene;
    Renderer* renderer = bench.renderer.get();
    const std::filesystem::path& dir = bench.dir;
    ReferenceCache cache(dir);
    auto key = MakeReferenceKey(scene, SceneFingerprint(scene), 0, 0.0, 0, Camera(), 4, 2, 1);
    bool hit = true;
    Plane<vec3> first = cache.GetOrRender(key, *renderer, &hit);
    CHECK_FALSE(hit);
    REQUIRE(std::filesystem::exists(cache.PathOf(key)));
    Plane<vec3> second = cache.GetOrRender(key, *renderer, &hit);
    CHECK(hit);
    REQUIRE(second.size() == first.size());
    for (size_t i = 0; i < first.size(); ++i) REQUIRE(second[i] == first[i]);
    // A new cache (a later run) finds the entry on disk, bit-exact.
    ReferenceCache later(dir);
    Plane<vec3> third = later.GetOrRender(key, *renderer, &hit);
    CHECK(hit);
    for (size_t i = 0; i < first.size(); ++i) REQUIRE(third[i] == first[i]);
}

TEST_CASE("reference cache never uses an entry made for another key or changed on disk", "[app]") {
    CornellCacheBench bench("fovrt_reference_cache_integrity_test");
    const Scene& scene = bench.scene;
    Renderer* renderer = bench.renderer.get();
    const std::filesystem::path& dir = bench.dir;
    const uint64_t fp = SceneFingerprint(scene);
    const auto eye0 = MakeReferenceKey(scene, fp, 0, 0.0, 0, Camera(), 4, 2, 1);
    const auto eye1 = MakeReferenceKey(scene, fp, 0, 0.0, 1, Camera(0.1f), 4, 2, 1);
    bool hit = true;
    Plane<vec3> image0, image1;
    {
        ReferenceCache cache(dir);
        image0 = cache.GetOrRender(eye0, *renderer, &hit);
        image1 = cache.GetOrRender(eye1, *renderer, &hit);
    }
    auto samePixels = [](const Plane<vec3>& a, const Plane<vec3>& b) {
        if (a.size() != b.size()) return false;
        for (size_t i = 0; i < a.size(); ++i)
            if (a[i] != b[i]) return false;
        return true;
    };
    REQUIRE_FALSE(samePixels(image0, image1));

    SECTION("eye 1's entry copied over eye 0's file is rendered again") {
        std::filesystem::copy_file(ReferenceCache(dir).PathOf(eye1), ReferenceCache(dir).PathOf(eye0),
                                   std::filesystem::copy_options::overwrite_existing);
        ReferenceCache cache(dir);
        CHECK_FALSE(cache.Find(eye0));  // the live error view shows nothing rather than a wrong image
        CHECK(samePixels(cache.GetOrRender(eye0, *renderer, &hit), image0));
        CHECK_FALSE(hit);
        CHECK(samePixels(ReferenceCache(dir).GetOrRender(eye0, *renderer, &hit), image0));  // and stored again
        CHECK(hit);
    }
    SECTION("an entry with flipped bytes is rendered again") {
        const auto path = ReferenceCache(dir).PathOf(eye0);
        std::string bytes;
        {
            std::ifstream in(path, std::ios::binary);
            bytes.assign(std::istreambuf_iterator<char>(in), {});
        }
        for (size_t i = bytes.size() / 2; i < bytes.size() / 2 + 8; ++i) bytes[i] = char(~bytes[i]);
        std::ofstream(path, std::ios::binary) << bytes;
        ReferenceCache cache(dir);
        CHECK(samePixels(cache.GetOrRender(eye0, *renderer, &hit), image0));
        CHECK_FALSE(hit);
    }
}

TEST_CASE("a reference above 1024 spp is the mean of 1024-spp chunks, the cached ones reused", "[app]") {
    CornellCacheBench bench("fovrt_reference_chunks_test");
    const Scene& scene = bench.scene;
    Renderer& renderer = *bench.renderer;
    const uint64_t fp = SceneFingerprint(scene);
    const auto key = MakeReferenceKey(scene, fp, 0, 0.0, 0, Camera(), 3 * kReferenceChunkSpp, 2, 7);
    REQUIRE(ReferenceChunks(key.spp) == 3);
    CHECK(ReferenceChunks(kReferenceChunkSpp) == 1);
    CHECK(ReferenceChunks(kReferenceChunkSpp + 1) == 1);  // not a multiple: one piece
    // Chunk 0 is the 1024-spp reference of the same seed; the others have seeds of their own.
    const auto single = MakeReferenceKey(scene, fp, 0, 0.0, 0, Camera(), kReferenceChunkSpp, 2, 7);
    CHECK(key.Chunk(0).Hex() == single.Hex());
    CHECK(key.Chunk(1).Hex() != single.Hex());
    CHECK(key.Chunk(1).spp == kReferenceChunkSpp);
    CHECK(key.Chunk(1).seed != key.Chunk(2).seed);
    CHECK(key.Hex() != MakeReferenceKey(scene, fp, 0, 0.0, 0, Camera(), 3 * kReferenceChunkSpp + 1, 2, 7).Hex());

    bool hit = true;
    Plane<vec3> chunk0, chunk1, chunk2, mean;
    {
        ReferenceCache cache(bench.dir);
        chunk0 = cache.GetOrRender(single, renderer, &hit);  // an earlier run's 1024-spp reference
        CHECK_FALSE(hit);
    }
    // Chunk 1 is rendered without the cache, to count what the 3072-spp reference then renders.
    renderer.RenderReference(0, Camera(), kReferenceChunkSpp, HashCombine(key.Chunk(1).seed, 0u), chunk1);
    {
        ReferenceCache cache(bench.dir);
        const uint64_t before = renderer.Stats().primaryRays;  // one per pixel and render
        mean = cache.GetOrRender(key, renderer, &hit);
        CHECK_FALSE(hit);
        // Chunks 1 and 2 are rendered; chunk 0 came from the cache.
        CHECK(renderer.Stats().primaryRays - before == 2u * 24u * 16u);
        chunk2 = cache.GetOrRender(key.Chunk(2), renderer, &hit);
        CHECK(hit);
        CHECK(std::filesystem::exists(cache.PathOf(key.Chunk(1))));
    }
    REQUIRE(mean.size() == chunk0.size());
    int differs = 0;
    for (size_t i = 0; i < mean.size(); ++i) {
        const vec3 expected = (chunk0[i] + chunk1[i] + chunk2[i]) / 3.0f;
        for (int c = 0; c < 3; ++c) REQUIRE(mean[i][c] == Approx(expected[c]).epsilon(1e-6).margin(1e-7));
        differs += chunk1[i] != chunk0[i];
    }
    CHECK(differs > int(mean.size()) / 2);  // independent chunks, not one image three times
    // Read back whole.
    ReferenceCache later(bench.dir);
    const Plane<vec3> again = later.GetOrRender(key, renderer, &hit);
    CHECK(hit);
    for (size_t i = 0; i < mean.size(); ++i) REQUIRE(again[i] == mean[i]);
}
