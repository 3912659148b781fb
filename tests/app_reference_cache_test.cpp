// Reference cache: keys change with everything that changes the image and nothing else, and a
// cached entry reads back exactly what was rendered.
#include <filesystem>

#include "app/reference_cache.h"
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

TEST_CASE("reference cache renders once, then reads back the same pixels", "[app]") {
    Scene scene = LoadScene(ResolveSceneName("cornell"));
    RenderSettings settings;
    auto renderer = CreateRenderer(scene, settings);
    renderer->SetFrame(0);
    auto dir = std::filesystem::temp_directory_path() / "fovrt_reference_cache_test";
    std::filesystem::remove_all(dir);
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
    std::filesystem::remove_all(dir);
}
