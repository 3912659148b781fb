// Roughness / metallic maps in scene files (issue #13): procedural patterns and their errors,
// the built-in brdf-detail scenes that use them.
#include <fstream>

#include "core/error.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace fovrt;

namespace {

std::filesystem::path WriteScene(const std::string& name, const std::string& material) {
    const auto dir = test::ScratchDir("fovrt-material-maps");
    std::filesystem::copy_file(test::SourceDir() / "scenes" / "brdf_panels.obj", dir / "brdf_panels.obj",
                               std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(test::SourceDir() / "scenes" / "brdf_panels.mtl", dir / "brdf_panels.mtl",
                               std::filesystem::copy_options::overwrite_existing);
    const auto path = dir / (name + ".toml");
    std::ofstream(path) << "[camera]\nposition = [0, 1, 3]\ntarget = [0, 1, 0]\n[[mesh]]\nfile = \"brdf_panels.obj\"\n"
                        << "[[material]]\nname = \"metal_panel\"\n" << material;
    return path;
}

}  // namespace

TEST_CASE("brdf-detail's panels carry procedural roughness maps at a few pixels' scale", "[scene]") {
    for (const char* name : {"brdf-detail", "brdf-detail-moving"}) {
        const Scene scene = LoadScene(ResolveSceneName(name));
        int mapped = 0;
        for (const Material& m : scene.materials) {
            if (m.roughnessTexture < 0) continue;
            ++mapped;
            const Texture& t = scene.textures[size_t(m.roughnessTexture)];
            CHECK(t.width == 128);  // 32 cells x 4 texels
            float lo = 1.0f, hi = 0.0f;
            for (const vec4& v : t.texels) {
                lo = std::min(lo, v.r);
                hi = std::max(hi, v.r);
            }
            CHECK(hi - lo >= 0.5f);  // rough and smooth cells
        }
        CHECK(mapped == 2);
    }
    CHECK(LoadScene(ResolveSceneName("brdf-detail-moving")).cameraPath.size() == 3);
}

TEST_CASE("scene-file roughness and metallic maps: patterns and errors name the key", "[scene]") {
    const Scene s = LoadScene(WriteScene(
        "ok", "roughness_texture = { pattern = \"checker\", cells = [2, 3], values = [0.1, 0.9], texels_per_cell = 1 }\n"
              "metallic_texture = { pattern = \"cells\", cells = [4, 4], values = [0, 1] }\n"));
    const Material* metal = nullptr;
    for (const Material& m : s.materials)
        if (m.name == "metal_panel") metal = &m;
    REQUIRE(metal != nullptr);
    REQUIRE(metal->roughnessTexture >= 0);
    REQUIRE(metal->metallicTexture >= 0);
    const Texture& r = s.textures[size_t(metal->roughnessTexture)];
    CHECK(r.width == 2);
    CHECK(r.height == 3);
    CHECK(r.texels[0].r == Approx(0.1f));
    CHECK(r.texels[1].r == Approx(0.9f));
    CHECK(s.textures[size_t(metal->metallicTexture)].width == 16);
    CHECK_THROWS_WITH(LoadScene(WriteScene("bad1", "roughness_texture = { pattern = \"stripes\", cells = [2, 2], values = [0, 1] }\n")),
                      Catch::Contains("material.roughness_texture.pattern") && Catch::Contains("stripes"));
    CHECK_THROWS_WITH(LoadScene(WriteScene("bad2", "metallic_texture = { cells = [2, 2], values = [0, 2] }\n")),
                      Catch::Contains("material.metallic_texture.values"));
    CHECK_THROWS_WITH(LoadScene(WriteScene("bad3", "roughness_texture = \"missing.png\"\n")),
                      Catch::Contains("missing.png"));
}
