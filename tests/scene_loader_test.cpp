// Scene loading: built-in scenes, shared assets (skipped when absent), formats and every bad-input
// case (each must be one fovrt::Error naming the file and the key/line).
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <filesystem>
#include <string>
#include <vector>
#include <tuple>
#include <unistd.h>

#include "core/error.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;

namespace {

// A fresh directory under the system temp dir, removed at scope exit.
struct TempDir {
    fs::path path;
    TempDir() {
        static int counter = 0;
        path = fs::temp_directory_path() /
               ("fovrt_scene_loader_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    fs::path Write(const std::string& name, const std::string& text) const {
        fs::path file = path / name;
        std::ofstream(file, std::ios::binary) << text;
        return file;
    }
};

const char* kCubeObj =
    "mtllib a.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "usemtl m\n"
    "f 1 2 3 4\n";
const char* kCubeMtl = "newmtl m\nKd 0.5 0.5 0.5\n";
const char* kMinimalScene =
    "name = \"t\"\n"
    "[[mesh]]\n"
    "file = \"a.obj\"\n";

// Loads `scene` and returns the fovrt::Error message (fails the test if it loads or throws
// anything else).
std::string ErrorOf(const fs::path& scene) {
    try {
        LoadScene(scene);
    } catch (const Error& e) {
        return e.what();
    } catch (const std::exception& e) {
        FAIL("not a fovrt::Error: " << e.what());
    }
    FAIL("loaded without error: " << scene.string());
    return {};
}

// The message is one line and names `file` (by file name) and each of `needles`.
void CheckMessage(const std::string& message, const fs::path& file, std::initializer_list<std::string> needles) {
    INFO("message: " << message);
    CHECK(message.find('\n') == std::string::npos);
    CHECK(message.find(file.filename().string()) != std::string::npos);
    for (const std::string& needle : needles) CHECK(message.find(needle) != std::string::npos);
}

vec3 WorldPoint(const Scene& scene, size_t instance, const vec3& p, float time = 0.0f) {
    return vec3(scene.instances[instance].WorldFromObjectAt(time) * vec4(p, 1.0f));
}

const Material* FindMaterial(const Scene& scene, const std::string& name) {
    for (const Material& m : scene.materials)
        if (m.name == name) return &m;
    return nullptr;
}

float SrgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

}  // namespace

TEST_CASE("built-in Cornell box", "[scene]") {
    Scene scene = LoadScene(ResolveSceneName("cornell"));
    CHECK(scene.name == "cornell");
    REQUIRE(scene.instances.size() == 3);  // room, short box, tall box (one cube mesh, shared)
    CHECK(scene.meshes.size() == 2);
    CHECK(CountTriangles(scene) == 36);
    CHECK(CountEmissiveTriangles(scene) == 2);
    const Material* red = FindMaterial(scene, "red");
    const Material* light = FindMaterial(scene, "light");
    REQUIRE(red);
    REQUIRE(light);
    CHECK(red->baseColor.r == Approx(0.63f));
    CHECK(light->emission.g == Approx(12.0f));
    // Roughness from Ns 10: sqrt(2 / 12); Ks 0: pure Lambert (specular weight 0).
    CHECK(red->roughness == Approx(std::sqrt(2.0f / 12.0f)));
    CHECK(red->specular == 0.0f);
    CHECK(scene.horizontalFovDegrees == 60.0f);
    // Short box: translate (0.35, 0, 0.3) * rotate(-17 deg about y) * scale 0.6 of corner (0.5, 1, 0.5).
    float a = Radians(-17.0f);
    vec3 local(0.3f, 0.6f, 0.3f);
    vec3 expected = vec3(0.35f, 0.0f, 0.3f) +
                    vec3(std::cos(a) * local.x + std::sin(a) * local.z, local.y,
                         -std::sin(a) * local.x + std::cos(a) * local.z);
    vec3 got = WorldPoint(scene, 1, vec3(0.5f, 1.0f, 0.5f));
    CHECK(got.x == Approx(expected.x).margin(1e-5));
    CHECK(got.y == Approx(expected.y).margin(1e-5));
    CHECK(got.z == Approx(expected.z).margin(1e-5));
    // Camera looks into the box down -z from 4.2 m.
    Pose head = scene.HeadAt(0.0f);
    CHECK(head.position.z == Approx(4.2f));
    vec3 forward = head.orientation * vec3(0, 0, -1);
    CHECK(forward.z == Approx(-1.0f));
}

TEST_CASE("built-in pillars and room", "[scene]") {
    Scene pillars = LoadScene(ResolveSceneName("pillars"));
    CHECK(pillars.instances.size() == 7);
    CHECK(CountTriangles(pillars) == 4 + 2 + 5 * 12);
    CHECK(CountEmissiveTriangles(pillars) == 2);
    for (size_t i = 2; i < 7; ++i) CHECK(pillars.instances[i].keys.size() == 3);

    Scene room = LoadScene(ResolveSceneName("room"));
    CHECK(room.instances.size() == 4);
    CHECK(CountTriangles(room) == 12 + 2 + 12 + 12);
    CHECK(CountEmissiveTriangles(room) == 2);
    REQUIRE(room.lights.size() == 2);
    CHECK(room.lights[0].type == LightType::Spot);
    CHECK(room.lights[1].switchPeriod == 2.0f);
    REQUIRE(room.emissionSwitches.size() == 1);
    CHECK(room.instances[room.emissionSwitches[0].instance].name == "lamp");
    CHECK(room.cameraPath.size() == 2);
    // The floor's checker texture: 16x16 sRGB, 4 px cells of (200,200,200) and (60,40,30).
    REQUIRE(room.textures.size() == 1);
    const Texture& checker = room.textures[0];
    CHECK(checker.width == 16);
    CHECK(checker.height == 16);
    CHECK(checker.texels[0].r == Approx(SrgbToLinear(200.0f / 255.0f)));
    CHECK(checker.texels[4].g == Approx(SrgbToLinear(40.0f / 255.0f)));
    CHECK(checker.texels[0].a == 1.0f);
    const Material* floor = FindMaterial(room, "room_floor");
    REQUIRE(floor);
    CHECK(floor->baseColorTexture == 0);
    // OBJ vt (0, 0) becomes uv (0, 1): v is flipped to the glTF convention.
    const Mesh& roomMesh = room.meshes[room.instances[0].mesh];
    REQUIRE(roomMesh.uvs.size() == roomMesh.positions.size());
    CHECK(roomMesh.uvs[0].x == 0.0f);
    CHECK(roomMesh.uvs[0].y == 1.0f);
}

TEST_CASE("glTF hierarchy is baked, materials and embedded buffers", "[scene]") {
    Scene scene = LoadScene(test::SourceDir() / "tests/data/scene/quad.gltf");
    REQUIRE(scene.instances.size() == 1);
    CHECK(scene.instances[0].name == "quad/quad");
    const Mesh& mesh = scene.meshes[scene.instances[0].mesh];
    REQUIRE(mesh.triangles.size() == 2);
    REQUIRE(mesh.positions.size() == 4);
    // world = T(0, 2, 0) * Ry(90) * S(2): (1, 1, 0) -> (0, 4, -2); normal (0, 0, 1) -> (1, 0, 0).
    CHECK(mesh.positions[2].x == Approx(0.0f).margin(1e-5));
    CHECK(mesh.positions[2].y == Approx(4.0f));
    CHECK(mesh.positions[2].z == Approx(-2.0f));
    CHECK(mesh.normals[0].x == Approx(1.0f));
    CHECK(mesh.uvs[1].x == 1.0f);
    REQUIRE(scene.materials.size() == 1);
    const Material& m = scene.materials[0];
    CHECK(m.name == "glow");
    CHECK(m.baseColor.g == Approx(0.25f));
    CHECK(m.metallic == Approx(0.25f));
    CHECK(m.roughness == Approx(0.75f));
    CHECK(m.emission.b == Approx(0.25f));
    CHECK(CountEmissiveTriangles(scene) == 2);
    CHECK(scene.background == vec3(0.0f));  // emissive: no default sky
}

TEST_CASE("binary glTF (.glb) loads like its .gltf", "[scene]") {
    std::ifstream in(test::SourceDir() / "tests/data/scene/quad.gltf");
    std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    while (json.size() % 4) json += ' ';
    // GLB: 12-byte header, then one JSON chunk (its buffer stays a data URI).
    auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    std::string glb = "glTF" + u32(2) + u32(uint32_t(12 + 8 + json.size())) + u32(uint32_t(json.size())) + "JSON" + json;
    TempDir dir;
    Scene scene = LoadScene(dir.Write("quad.glb", glb));
    REQUIRE(scene.instances.size() == 1);
    CHECK(scene.meshes[0].positions[2].y == Approx(4.0f));
    CHECK(CountEmissiveTriangles(scene) == 2);
    auto bad = dir.Write("bad.glb", glb.substr(0, 20));
    CheckMessage(ErrorOf(bad), bad, {"cannot load glTF"});
}

TEST_CASE("emission sides: glTF doubleSided, mirrored nodes, the scene-file key", "[scene]") {
    std::ifstream in(test::SourceDir() / "tests/data/scene/quad.gltf");
    std::string quad((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    TempDir dir;
    // The winding's normal (the side a one-sided emitter lights) agrees with the authored normal,
    // also under a mirroring node matrix, where glTF makes clockwise the front.
    auto windingAgreesWithNormal = [](const Scene& scene) {
        const Mesh& mesh = scene.meshes[scene.instances[0].mesh];
        const uvec3& t = mesh.triangles[0];
        vec3 winding = glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]);
        return glm::dot(winding, mesh.normals[t.x]) > 0.0f;
    };
    Scene plain = LoadScene(test::SourceDir() / "tests/data/scene/quad.gltf");
    CHECK_FALSE(plain.materials[0].emissionTwoSided);  // glTF's default doubleSided = false
    CHECK(windingAgreesWithNormal(plain));
    std::string mirrored = quad;
    REQUIRE(mirrored.find("\"scale\": [\n    2,") != std::string::npos);
    mirrored.replace(mirrored.find("\"scale\": [\n    2,"), 17, "\"scale\": [\n    -2,");
    CHECK(windingAgreesWithNormal(LoadScene(dir.Write("mirrored.gltf", mirrored))));
    std::string doubleSided = quad;
    doubleSided.replace(doubleSided.find("\"name\": \"glow\","), 15, "\"name\": \"glow\", \"doubleSided\": true,");
    CHECK(LoadScene(dir.Write("double.gltf", doubleSided)).materials[0].emissionTwoSided);
    // OBJ has no such flag: the scene file's material override sets it.
    auto one = dir.Write("one.toml", "[[mesh]]\nfile = \"" + (BuiltinScenesDir() / "cornell_room.obj").string() + "\"\n");
    auto two = dir.Write("two.toml", "[[mesh]]\nfile = \"" + (BuiltinScenesDir() / "cornell_room.obj").string() +
                                         "\"\n[[material]]\nname = \"light\"\nemission_two_sided = true\n");
    CHECK_FALSE(FindMaterial(LoadScene(one), "light")->emissionTwoSided);
    CHECK(FindMaterial(LoadScene(two), "light")->emissionTwoSided);
    auto bad = dir.Write("bad.toml", "[[mesh]]\nfile = \"" + (BuiltinScenesDir() / "cornell_room.obj").string() +
                                         "\"\n[[material]]\nname = \"light\"\nemission_two_sided = 1\n");
    CheckMessage(ErrorOf(bad), bad, {"emission_two_sided"});
}

TEST_CASE("bare mesh gets a camera framing its bounding box", "[scene]") {
    Scene scene = LoadScene(BuiltinScenesDir() / "cube.obj");
    REQUIRE(scene.instances.size() == 1);
    CHECK(CountTriangles(scene) == 12);
    CHECK(scene.background == vec3(1.0f));  // no emitters: white sky
    Pose head = scene.HeadAt(0.0f);
    vec3 forward = head.orientation * vec3(0, 0, -1);
    // Looks at the cube's centre (0, 0.5, 0) from +z, far enough to contain its bounding sphere.
    CHECK(head.position.x == Approx(0.0f).margin(1e-5));
    CHECK(head.position.y == Approx(0.5f));
    CHECK(forward.z == Approx(-1.0f));
    CHECK(head.position.z > std::sqrt(3.0f) * 0.5f / std::sin(Radians(30.0f)) * 0.99f);
}

TEST_CASE("scene names and directories", "[scene]") {
    CHECK(ResolveSceneName("cornell") == BuiltinScenesDir() / "cornell.toml");
    CHECK(ResolveSceneName("veach-ajar").filename() == "veach-ajar.toml");
    CHECK_THROWS_AS(ResolveSceneName("no-such-scene"), Error);
    TempDir dir;
    dir.Write("cornell.toml", kMinimalScene);
    ::setenv("FOVRT_SCENES_DIR", dir.path.c_str(), 1);
    CHECK(ResolveSceneName("cornell") == dir.path / "cornell.toml");
    ::unsetenv("FOVRT_SCENES_DIR");
    CHECK(ResolveSceneName("cornell") != dir.path / "cornell.toml");
    ::setenv("FOVRT_SHARED_SCENES", "/some/where", 1);
    CHECK(SharedScenesDir() == fs::path("/some/where"));
    ::unsetenv("FOVRT_SHARED_SCENES");
}

TEST_CASE("shared Cornell box and glTF samples", "[scene][shared]") {
    FOVRT_REQUIRE_SHARED_SCENES();
    Scene cornell = LoadScene(ResolveSceneName("cornell-shared"));
    CHECK(CountTriangles(cornell) == 36);  // 18 quads after triangulation
    CHECK(CountEmissiveTriangles(cornell) == 2);
    const Material* shortBox = FindMaterial(cornell, "shortBox");
    REQUIRE(shortBox);
    // Kd 0, Ks 0.725..: a metal with base colour Ks; Ns 200 -> roughness sqrt(2 / 202).
    CHECK(shortBox->metallic == Approx(1.0f));
    CHECK(shortBox->baseColor.r == Approx(0.725f));
    CHECK(shortBox->roughness == Approx(std::sqrt(2.0f / 202.0f)));
    CHECK(shortBox->specular == 1.0f);

    Scene box = LoadScene(ResolveSceneName("box"));
    CHECK(CountTriangles(box) == 12);
    CHECK(box.lights.size() == 1);
    REQUIRE(box.materials.size() == 1);
    CHECK(box.materials[0].metallic == 0.0f);  // overridden in box.toml
    CHECK(box.materials[0].specular == 1.0f);  // glTF default
    CHECK(box.materials[0].baseColor.r == Approx(0.8f));
    // Box.gltf's node matrix only rotates: the baked cube still spans [-0.5, 0.5]^3.
    for (const vec3& p : box.meshes[0].positions) CHECK(std::fabs(p.x) == Approx(0.5f));

    Scene suzanne = LoadScene(ResolveSceneName("suzanne"));
    CHECK(CountTriangles(suzanne) == 3936);
    REQUIRE(suzanne.textures.size() == 2);
    const Material& m = suzanne.materials[0];
    REQUIRE(m.baseColorTexture >= 0);
    REQUIRE(m.metallicRoughnessTexture >= 0);
    CHECK(suzanne.textures[size_t(m.baseColorTexture)].width == 1024);
    CHECK(suzanne.textures[size_t(m.metallicRoughnessTexture)].height == 1024);
    // The files it read, each once: the scene file, the glTF, its buffer and its two images.
    std::vector<std::string> files;
    for (const std::filesystem::path& file : suzanne.files) files.push_back(file.filename().string());
    CHECK(files == std::vector<std::string>{"suzanne.toml", "Suzanne.gltf", "Suzanne.bin", "Suzanne_BaseColor.png",
                                            "Suzanne_MetallicRoughness.png"});
    const Mesh& mesh = suzanne.meshes[0];
    CHECK(mesh.uvs.size() == mesh.positions.size());
    CHECK(mesh.normals.size() == mesh.positions.size());
    for (const Scene* scene : {&cornell, &box, &suzanne}) CHECK_NOTHROW(RequireSceneLight(*scene));
}

TEST_CASE("shared Veach Ajar", "[scene][shared]") {
    FOVRT_REQUIRE_SHARED_SCENES();
    Scene scene = LoadScene(ResolveSceneName("veach-ajar"));  // the only load of the 39 MB OBJ
    size_t triangles = CountTriangles(scene);
    CHECK(triangles > 380000);
    CHECK(triangles < 386000);
    CHECK(CountEmissiveTriangles(scene) == 2);
    Pose head = scene.HeadAt(0.0f);
    CHECK(head.position.x == Approx(4.05402f));
    CHECK(head.position.y == Approx(1.61647f));
    CHECK(head.position.z == Approx(-2.30652f));
    // Forward = Mitsuba's local +Z (column 2), up = column 1, right = -column 0.
    vec3 forward = head.orientation * vec3(0, 0, -1);
    vec3 right = head.orientation * vec3(1, 0, 0);
    CHECK(forward.x == Approx(-0.990015f).margin(1e-4));
    CHECK(forward.z == Approx(-0.137213f).margin(1e-4));
    CHECK(right.x == Approx(0.137283f).margin(1e-4));
    CHECK(right.z == Approx(-0.990532f).margin(1e-4));
    CHECK(scene.horizontalFovDegrees == 60.0f);
    REQUIRE(scene.textures.size() == 3);
    for (const Texture& t : scene.textures) {
        CHECK(t.width > 0);
        CHECK(t.texels.size() == size_t(t.width) * size_t(t.height));
    }
    const Material* light = FindMaterial(scene, "Light");
    REQUIRE(light);
    CHECK(light->emission.r == 300.0f);
    CHECK_NOTHROW(RequireSceneLight(scene));
}

TEST_CASE("bad scene files give one fovrt::Error naming file and key", "[scene][errors]") {
    TempDir dir;
    dir.Write("a.obj", kCubeObj);
    dir.Write("a.mtl", kCubeMtl);
    REQUIRE_NOTHROW(LoadScene(dir.Write("ok.toml", kMinimalScene)));

    SECTION("missing scene file") {
        CheckMessage(ErrorOf(dir.path / "absent.toml"), dir.path / "absent.toml", {"not found"});
    }
    SECTION("TOML syntax error") {
        auto f = dir.Write("s.toml", "name = \"t\"\n[[mesh]\nfile = 3\n");
        CheckMessage(ErrorOf(f), f, {"s.toml:2"});
    }
    SECTION("unknown top-level key") {
        auto f = dir.Write("s.toml", "colour = 1\n" + std::string(kMinimalScene));
        CheckMessage(ErrorOf(f), f, {"s.toml:1", "unknown key 'colour'"});
    }
    SECTION("unknown nested key") {
        auto f = dir.Write("s.toml", std::string(kMinimalScene) + "spin = 3\n");
        CheckMessage(ErrorOf(f), f, {"mesh[0].spin", ":4"});
    }
    SECTION("wrong value type") {
        auto f = dir.Write("s.toml", "frame_rate = \"fast\"\n" + std::string(kMinimalScene));
        CheckMessage(ErrorOf(f), f, {"frame_rate", "number"});
    }
    SECTION("missing mesh file") {
        auto f = dir.Write("s.toml", "[[mesh]]\nfile = \"gone.obj\"\n");
        CheckMessage(ErrorOf(f), f, {"mesh[0].file", "gone.obj", "not found"});
    }
    SECTION("unknown light type and unsorted keys") {
        auto f = dir.Write("s.toml", std::string(kMinimalScene) + "[[light]]\ntype = \"laser\"\n");
        CheckMessage(ErrorOf(f), f, {"light[0].type", "laser"});
        f = dir.Write("s.toml", std::string(kMinimalScene) +
                                    "keys = [{ time = 1, translate = [0, 0, 0] }, { time = 0 }]\n");
        CheckMessage(ErrorOf(f), f, {"mesh[0].keys", "increase"});
    }
    SECTION("unknown material override") {
        auto ok = dir.Write("o.toml", std::string(kMinimalScene) + "[[material]]\nname = \"m\"\nspecular = 0.5\n");
        CHECK(LoadScene(ok).materials[0].specular == 0.5f);
        auto f = dir.Write("s.toml", std::string(kMinimalScene) + "[[material]]\nname = \"nope\"\nroughness = 0.5\n");
        CheckMessage(ErrorOf(f), f, {"material.name", "unknown material 'nope'"});
    }
    SECTION("unknown emission-switch instance") {
        auto f = dir.Write("s.toml", std::string(kMinimalScene) + "[[emission_switch]]\ninstance = \"x\"\nperiod = 1\n");
        CheckMessage(ErrorOf(f), f, {"emission_switch[0].instance", "unknown instance 'x'"});
    }
    SECTION("camera needs exactly one form") {
        auto f = dir.Write("s.toml", std::string(kMinimalScene) + "[camera]\nposition = [0, 0, 1]\n");
        CheckMessage(ErrorOf(f), f, {"camera.target", "missing"});
    }
    SECTION("OBJ: non-finite, out-of-range, malformed, unknown material, missing MTL") {
        auto scene = dir.Write("s.toml", "[[mesh]]\nfile = \"b.obj\"\n");
        dir.Write("b.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
        CheckMessage(ErrorOf(scene), scene, {"b.obj:2", "not finite", "mesh[0].file"});
        dir.Write("b.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n");
        CheckMessage(ErrorOf(scene), scene, {"b.obj:2", "not finite"});
        dir.Write("b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
        CheckMessage(ErrorOf(scene), scene, {"b.obj:4", "out of range"});
        dir.Write("b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n");
        CheckMessage(ErrorOf(scene), scene, {"b.obj:4", "out of range"});
        dir.Write("b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n");
        CheckMessage(ErrorOf(scene), scene, {"b.obj:4", "malformed"});
        // tinyobjloader reads "-1.0x" as -1 and ignores a fourth (or seventh) token.
        dir.Write("b.obj", "v 0 0 0\nv -1.0x 0 1\nv 0 1 0\nf 1 2 3\n");
        CheckMessage(ErrorOf(scene), scene, {"b.obj:2", "malformed number '-1.0x'"});
        dir.Write("b.obj", "v 0 0 0\nv -1 0 1 junk\nv 0 1 0\nf 1 2 3\n");
        CheckMessage(ErrorOf(scene), scene, {"b.obj:2", "malformed number 'junk'"});
        dir.Write("b.obj", "v 0 0 0\nv 1 0 0 1 1\nv 0 1 0\nf 1 2 3\n");
        CheckMessage(ErrorOf(scene), scene, {"b.obj:2", "'v' has 5 numbers"});
        dir.Write("b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1 0\nf 1 2 3\n");
        CheckMessage(ErrorOf(scene), scene, {"b.obj:4", "'vn' has 4 numbers"});
        dir.Write("b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.5e\nf 1 2 3\n");
        CheckMessage(ErrorOf(scene), scene, {"b.obj:4", "malformed number '0.5e'"});
        // The forms tinyobjloader reads stay accepted: w, vertex colours, a trailing comment.
        dir.Write("b.obj", "v 0 0 0 1\nv 1 0 0 0.5 0.5 0.5\nv 0 1 0 # top\nvt 0.5\nf 1 2 3\n");
        CHECK_NOTHROW(LoadScene(scene));
        dir.Write("b.obj", "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl nope\nf 1 2 3\n");
        CheckMessage(ErrorOf(scene), scene, {"b.obj:5", "usemtl 'nope'"});
        dir.Write("b.obj", "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        CheckMessage(ErrorOf(scene), scene, {"b.obj", "mtllib", "gone.mtl"});
        dir.Write("b.obj", "v 0 0 0\n");
        CheckMessage(ErrorOf(scene), scene, {"b.obj", "no faces"});
    }
    SECTION("MTL colours: the same check as the scene file's material override, with file:line") {
        auto scene = dir.Write("s.toml", "[[mesh]]\nfile = \"c.obj\"\n");
        dir.Write("c.obj", "mtllib c.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl lamp\nf 1 2 3\n");
        const std::vector<std::pair<std::string, std::string>> bad = {
            {"Ke 3e38 3e38 3e38", "is above 1e+09"},  // finite, but its square is inf in float
            {"Kd nan 0.5 0.5", "not a finite number"},  // tinyobjloader substitutes a value
            {"Ks 0.1 -0.2 0.1", "must be >= 0"},
            {"Ke inf 1 1", "not a finite number"},
            {"Kd 0.5 x 0.5", "malformed number 'x'"},
            {"Ns nan", "not a finite number"}};
        for (const auto& [line, problem] : bad) {
            INFO(line);
            dir.Write("c.mtl", "# lamp\nnewmtl lamp\n" + line + "\n");
            const std::string key = line.substr(0, 2);
            CheckMessage(ErrorOf(scene), scene, {"c.mtl:3", "material 'lamp'", key + ": ", problem});
        }
        dir.Write("c.mtl", "newmtl lamp\nKd 0.5 0.5 0.5\nKe 300 300 300\n");
        CHECK(LoadScene(scene).materials[0].emission == vec3(300.0f));
        // The override refuses what the MTL refuses.
        auto f = dir.Write("e.toml", std::string(kMinimalScene) + "[[material]]\nname = \"m\"\nemission = 2e9\n");
        CheckMessage(ErrorOf(f), f, {"e.toml:6", "material.emission", "is above 1e+09"});
        f = dir.Write("e.toml", std::string(kMinimalScene) + "[[material]]\nname = \"m\"\nbase_color = [1, -1, 1]\n");
        CheckMessage(ErrorOf(f), f, {"material.base_color", "must be >= 0"});
    }
    SECTION("glTF material colours: the MTL's rule, naming the file and the material") {
        std::ifstream in(test::SourceDir() / "tests/data/scene/quad.gltf");
        const std::string quad((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::string authored = "\"emissiveFactor\": [\n    1,\n    0.5,\n    0.25\n   ]";
        REQUIRE(quad.find(authored) != std::string::npos);
        auto scene = dir.Write("s.toml", "[[mesh]]\nfile = \"q.gltf\"\n");
        // The quad's material 'glow' with its emission (and, once, its base colour) replaced.
        const std::string authoredBase = "\"baseColorFactor\": [\n     0.5,\n     0.25,\n     1,\n     1\n    ]";
        REQUIRE(quad.find(authoredBase) != std::string::npos);
        auto withEmission = [&](const std::string& emission, const std::string& baseColor = "") {
            std::string text = quad;
            text.replace(text.find(authored), authored.size(), emission);
            if (!baseColor.empty()) text.replace(text.find(authoredBase), authoredBase.size(), baseColor);
            dir.Write("q.gltf", text);
        };
        auto strength = [](const std::string& value) {
            return "\"emissiveFactor\": [1, 1, 1], \"extensions\": "
                   "{\"KHR_materials_emissive_strength\": {\"emissiveStrength\": " + value + "}}";
        };
        const std::vector<std::tuple<std::string, std::string, std::string, std::string>> bad = {
            {"\"emissiveFactor\": [3e38, 3e38, 3e38]", "", "emissiveFactor: ", "is above 1e+09"},
            {"\"emissiveFactor\": [1, -0.5, 1]", "", "emissiveFactor: ", "must be >= 0"},
            {"\"emissiveFactor\": [0, 0, 0]", "\"baseColorFactor\": [0.5, -1, 0.5, 1]",
             "pbrMetallicRoughness.baseColorFactor: ", "must be >= 0"},
            {"\"emissiveFactor\": [0, 0, 0]", "\"baseColorFactor\": [2e9, 0.5, 0.5, 1]",
             "pbrMetallicRoughness.baseColorFactor: ", "is above 1e+09"},
            {strength("-2"), "", "KHR_materials_emissive_strength.emissiveStrength: ", "must be >= 0"},
            {strength("\"bright\""), "", "KHR_materials_emissive_strength.emissiveStrength: ", "not a number"},
            // Each factor within the rule, their product (the radiance rendered) not.
            {"\"emissiveFactor\": [1, 1e5, 1], \"extensions\": "
             "{\"KHR_materials_emissive_strength\": {\"emissiveStrength\": 1e5}}",
             "", "emissiveFactor * KHR_materials_emissive_strength.emissiveStrength: ", "10000000000 is above 1e+09"}};
        for (const auto& [emission, baseColor, key, problem] : bad) {
            INFO(emission << " " << baseColor);
            withEmission(emission, baseColor);
            CheckMessage(ErrorOf(scene), scene, {"q.gltf", "material 'glow'", key, problem});
        }
        withEmission(strength("300"));
        CHECK(LoadScene(scene).materials[0].emission == vec3(300.0f));
    }
    SECTION("textures: missing and corrupt") {
        auto scene = dir.Write("s.toml", "[[mesh]]\nfile = \"t.obj\"\n");
        dir.Write("t.obj", "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl tex\nf 1 2 3\n");
        dir.Write("t.mtl", "newmtl tex\nKd 1 1 1\nmap_Kd gone.png\n");
        CheckMessage(ErrorOf(scene), scene, {"t.mtl", "map_Kd", "gone.png", "not found"});
        dir.Write("t.mtl", "newmtl tex\nKd 1 1 1\nmap_Kd bad.png\n");
        dir.Write("bad.png", "\x89PNG\r\n\x1a\nthis is not a png");
        CheckMessage(ErrorOf(scene), scene, {"bad.png", "cannot decode"});
        auto f = dir.Write("o.toml", std::string(kMinimalScene) +
                                         "[[material]]\nname = \"m\"\nbase_color_texture = \"bad.png\"\n");
        CheckMessage(ErrorOf(f), f, {"base_color_texture", "bad.png"});
    }
    SECTION("glTF: corrupt JSON, bad index, non-finite vertex, missing buffer") {
        std::ifstream in(test::SourceDir() / "tests/data/scene/quad.gltf");
        std::string quad((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        REQUIRE(quad.size() > 100);
        auto scene = dir.Write("s.toml", "[[mesh]]\nfile = \"q.gltf\"\n");
        dir.Write("q.gltf", quad.substr(0, quad.size() / 2));
        CheckMessage(ErrorOf(scene), scene, {"q.gltf", "mesh[0].file"});
        // Index accessor pointing past the accessor list.
        std::string bad = quad;
        bad.replace(bad.find("\"indices\": 3"), 12, "\"indices\": 9");
        dir.Write("q.gltf", bad);
        CheckMessage(ErrorOf(scene), scene, {"q.gltf", "indices"});
        // External buffer that does not exist.
        bad = quad;
        size_t uri = bad.find("data:application");
        bad.replace(uri, bad.find('"', uri) - uri, "missing.bin");
        dir.Write("q.gltf", bad);
        CheckMessage(ErrorOf(scene), scene, {"q.gltf"});
        // A quad vertex count beyond the buffer view.
        bad = quad;
        bad.replace(bad.find("\"count\": 4"), 10, "\"count\": 9");
        dir.Write("q.gltf", bad);
        CheckMessage(ErrorOf(scene), scene, {"q.gltf", "exceeds"});
    }
}

TEST_CASE("a scene with no light is refused for rendering, naming the scene; every shipped scene has light",
          "[scene][errors]") {
    TempDir dir;
    dir.Write("a.obj", kCubeObj);
    dir.Write("a.mtl", kCubeMtl);
    const fs::path dark = dir.Write("dark.toml", kMinimalScene);
    const Scene unlit = LoadScene(dark);  // loading alone asks for no light
    try {
        RequireSceneLight(unlit);
        FAIL("an unlit scene passed");
    } catch (const Error& e) {
        CheckMessage(e.what(), dark, {"scene 't'", "has no light"});
    }
    // A light that gives nothing is no light either; any one source of radiance is enough.
    const std::string off = "\n[[light]]\ntype = \"point\"\nposition = [0, 2, 0]\nintensity = 0\n";
    CHECK_THROWS_WITH(RequireSceneLight(LoadScene(dir.Write("off.toml", kMinimalScene + off))),
                      Catch::Contains("has no light"));
    const std::string on = "\n[[light]]\ntype = \"point\"\nposition = [0, 2, 0]\nintensity = 1\n";
    CHECK_NOTHROW(RequireSceneLight(LoadScene(dir.Write("on.toml", kMinimalScene + on))));
    CHECK_NOTHROW(RequireSceneLight(LoadScene(dir.Write("sky.toml", "background = [0, 0, 0.1]\n" +
                                                                          std::string(kMinimalScene)))));
    dir.Write("a.mtl", "newmtl m\nKd 0.5 0.5 0.5\nKe 1 1 1\n");
    CHECK_NOTHROW(RequireSceneLight(LoadScene(dark)));

    for (const char* name : {"cornell", "pillars", "room", "brdf-detail", "brdf-detail-moving"})
        CHECK_NOTHROW(RequireSceneLight(LoadScene(ResolveSceneName(name))));
    CHECK_NOTHROW(RequireSceneLight(LoadScene(BuiltinScenesDir() / "cube.obj")));  // a bare mesh gets a sky
}

TEST_CASE("glTF non-finite vertices and out-of-range indices are rejected", "[scene][errors]") {
    // Positions: 3 floats of which one is NaN; indices referencing vertex 7 of 3.
    TempDir dir;
    auto write = [&](const std::string& name, float nanOrZero, uint16_t index) {
        unsigned char buf[36 + 8] = {};
        float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, nanOrZero};
        std::memcpy(buf, pos, 36);
        uint16_t idx[3] = {0, 1, index};
        std::memcpy(buf + 36, idx, 6);
        static const char* b64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        std::string enc;
        for (size_t i = 0; i < sizeof(buf); i += 3) {
            uint32_t v = uint32_t(buf[i]) << 16 | uint32_t(i + 1 < sizeof(buf) ? buf[i + 1] : 0) << 8 |
                         uint32_t(i + 2 < sizeof(buf) ? buf[i + 2] : 0);
            enc += b64[(v >> 18) & 63];
            enc += b64[(v >> 12) & 63];
            enc += i + 1 < sizeof(buf) ? b64[(v >> 6) & 63] : '=';
            enc += i + 2 < sizeof(buf) ? b64[v & 63] : '=';
        }
        std::string json =
            R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
            R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
            R"("buffers":[{"byteLength":44,"uri":"data:application/octet-stream;base64,)" + enc + R"("}],)"
            R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],)"
            R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},)"
            R"({"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})";
        return dir.Write(name, json);
    };
    REQUIRE_NOTHROW(LoadScene(write("ok.gltf", 0.0f, 2)));
    auto f = write("nan.gltf", std::nanf(""), 2);
    CheckMessage(ErrorOf(f), f, {"POSITION", "vertex 2", "not finite"});
    f = write("index.gltf", 0.0f, 7);
    CheckMessage(ErrorOf(f), f, {"out of range"});
}
