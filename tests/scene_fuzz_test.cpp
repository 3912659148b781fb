// Randomised robustness: mutate valid scene/OBJ/MTL/glTF files (byte flips, truncation, garbage
// and duplicated lines) and load them. The loader must succeed or throw fovrt::Error: never
// crash, hang or throw anything else. Fixed seed, a few thousand iterations.
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>

#include "core/error.h"
#include "core/rng.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;

namespace {

std::string ReadText(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    REQUIRE(in);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void WriteText(const fs::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
}

const char* kScene = R"(name = "fuzz"
frame_rate = 30
background = [0.1, 0.1, 0.1]
fov = 60

[camera]
keys = [
  { time = 0, position = [0, 1, 4], target = [0, 1, 0] },
  { time = 2, position = [1, 1, 4], target = [0, 1, 0], up = [0, 1, 0] },
]

[[mesh]]
name = "room"
file = "room.obj"

[[mesh]]
name = "box"
file = "cube.obj"
translate = [0.3, 0, 0.2]
rotate = { degrees = 20, axis = [0, 1, 0] }
scale = [0.5, 1, 0.5]
keys = [{ time = 0 }, { time = 1, rotate = [0, 45, 0] }]

[[mesh]]
name = "quad"
file = "quad.gltf"
loop = true

[[material]]
name = "white"
roughness = 0.5

[[light]]
type = "spot"
position = [0, 1.9, 0]
target = [0, 0, 0]
inner_degrees = 10
keys = [{ time = 0, position = [0, 1.9, 0] }, { time = 1, position = [0.5, 1.9, 0] }]
switch = { period = 1, on = 0.5 }

[[emission_switch]]
instance = "quad"
period = 0.5
on = 0.25
)";

const char* kGarbage[] = {
    "f 1 2 3",    "f -1 -2 -3", "f 0 0 0",     "v nan 1 2", "v 1e40 0 0", "usemtl nope",  "mtllib x.mtl",
    "vt 0.5",     "vn 0 0",     "f 1/1/1 2//2", "[[mesh]]",   "file = 3",    "x = [",      "[camera]",
    "keys = []",  "map_Kd q.png", "newmtl",     "Ke 1e39 0 0", "\"accessors\": [", "}", "{\"count\": 99999999999}",
    "\xff\xfe\x00", "rotate = { degrees = 1e30, axis = [0, 0, 0] }", "scale = -1", "time = nan",
};

}  // namespace

TEST_CASE("fuzzed scene inputs throw fovrt::Error or load", "[scene][fuzz]") {
    const fs::path builtin = test::SourceDir() / "scenes";
    std::vector<std::pair<std::string, std::string>> corpus = {
        {"scene.toml", kScene},
        {"room.obj", ReadText(builtin / "cornell_room.obj")},
        {"cornell_room.mtl", ReadText(builtin / "cornell_room.mtl")},
        {"cube.obj", ReadText(builtin / "cube.obj")},
        {"cube.mtl", ReadText(builtin / "cube.mtl")},
        {"quad.gltf", ReadText(test::SourceDir() / "tests/data/scene/quad.gltf")},
    };
    fs::path dir = fs::temp_directory_path() / ("fovrt_scene_fuzz_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    for (const auto& [name, text] : corpus) WriteText(dir / name, text);
    // The unmutated corpus loads.
    REQUIRE_NOTHROW(LoadScene(dir / "scene.toml"));

    // FOVRT_FUZZ_SEED / FOVRT_FUZZ_ITERATIONS allow longer soak runs (e.g. under ASan).
    const char* seedEnv = std::getenv("FOVRT_FUZZ_SEED");
    const char* iterationsEnv = std::getenv("FOVRT_FUZZ_ITERATIONS");
    Pcg32 rng(seedEnv ? std::strtoull(seedEnv, nullptr, 10) : 20261121ull);
    const int kIterations = iterationsEnv ? std::max(1, std::atoi(iterationsEnv)) : 3000;
    int loaded = 0, rejected = 0;
    for (int iteration = 0; iteration < kIterations; ++iteration) {
        size_t target = rng.NextBounded(uint32_t(corpus.size()));
        std::string text = corpus[target].second;
        int mutations = 1 + int(rng.NextBounded(3));
        for (int m = 0; m < mutations && !text.empty(); ++m) {
            size_t at = rng.NextBounded(uint32_t(text.size()));
            switch (rng.NextBounded(5)) {
            case 0:  // flip bits of one byte
                text[at] = char(text[at] ^ char(1u << rng.NextBounded(8)));
                break;
            case 1:  // random byte
                text[at] = char(rng.NextBounded(256));
                break;
            case 2:  // truncate
                text.resize(at);
                break;
            case 3: {  // insert a garbage line at a line start
                size_t line = text.rfind('\n', at);
                line = line == std::string::npos ? 0 : line + 1;
                const char* g = kGarbage[rng.NextBounded(uint32_t(std::size(kGarbage)))];
                text.insert(line, std::string(g) + "\n");
                break;
            }
            default: {  // duplicate or delete a line
                size_t begin = text.rfind('\n', at);
                begin = begin == std::string::npos ? 0 : begin + 1;
                size_t end = text.find('\n', at);
                end = end == std::string::npos ? text.size() : end + 1;
                std::string line = text.substr(begin, end - begin);
                if (rng.NextBounded(2)) text.insert(begin, line);
                else text.erase(begin, end - begin);
            }
            }
        }
        WriteText(dir / corpus[target].first, text);
        try {
            Scene scene = LoadScene(dir / "scene.toml");
            // Whatever loaded must be usable.
            SceneState state = scene.StateAt(0.5f);
            CHECK(state.worldFromObject.size() == scene.instances.size());
            for (const Instance& instance : scene.instances) CHECK(instance.mesh < scene.meshes.size());
            ++loaded;
        } catch (const Error& e) {
            std::string message = e.what();
            if (message.empty() || message.find('\n') != std::string::npos)
                FAIL("error message is not one line: '" << message << "'");
            ++rejected;
        } catch (const std::exception& e) {
            FAIL("iteration " << iteration << " (" << corpus[target].first << "): non-fovrt exception: " << e.what());
        }
        WriteText(dir / corpus[target].first, corpus[target].second);  // restore
    }
    std::error_code ec;
    fs::remove_all(dir, ec);
    INFO("loaded " << loaded << ", rejected " << rejected);
    CHECK(loaded + rejected == kIterations);
    if (kIterations >= 100) {
        CHECK(rejected > kIterations / 10);  // the mutations do hit the validators
        CHECK(loaded > 0);
    }
    std::printf("scene fuzz: %d iterations, %d loaded, %d rejected with fovrt::Error\n", kIterations, loaded, rejected);
}
