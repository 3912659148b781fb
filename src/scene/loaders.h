// Internal to fovrt_scene: mesh-file and texture loaders that append to a Scene under load.
#pragma once

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.h"

namespace fovrt::detail {

// One instance-to-be produced by a mesh file: its mesh and a name ("" for the file's only part,
// else the glTF node name).
struct MeshPart {
    uint32_t mesh = 0;
    std::string name;
};

// State shared by the loaders of one LoadScene() call: caches so that a file or texture named
// twice is decoded once.
struct LoadContext {
    Scene& scene;
    std::map<std::pair<std::string, bool>, int> textures;      // (path, srgb) -> index
    std::map<std::string, std::vector<MeshPart>> meshFiles;     // path -> parts

    // Records a file the load reads (Scene::files), once.
    void Read(const std::filesystem::path& file) {
        const std::filesystem::path normal = file.lexically_normal();
        if (std::find(scene.files.begin(), scene.files.end(), normal) == scene.files.end()) scene.files.push_back(normal);
    }
};

std::vector<MeshPart> LoadObj(const std::filesystem::path& file, LoadContext& context);
std::vector<MeshPart> LoadGltf(const std::filesystem::path& file, LoadContext& context);

// Decodes an image file (PNG/JPEG/TGA/BMP/HDR... through stb_image) into a linear texture;
// `srgb` converts 8-bit colour channels from sRGB. `referrer` names who asked (file + key) for
// the error message. Returns the index in scene.textures.
int LoadTextureFile(const std::filesystem::path& file, bool srgb, const std::string& referrer,
                    LoadContext& context);

// A procedural two-valued scalar texture (value in R, G, B; alpha 1): cellsX × cellsY cells of
// texelsPerCell² texels each, alternating a / b (checker) or a / b by a hash of the cell (cells).
Texture PatternTexture(const std::string& name, bool hashed, int cellsX, int cellsY, float a, float b,
                       int texelsPerCell);

// Converts 8-bit texel data (1-4 channels) into a Texture; 16-bit when bits == 16.
Texture TextureFromPixels(const std::string& path, int width, int height, int channels, int bits,
                          const unsigned char* data, bool srgb);

// The largest colour component a material may have (base colour, Kd, Ks, emission, Ke): the
// square of a radiance (SVGF's second moments, squared errors) must stay finite in 32-bit float
// (max 3.4e38) even summed over a frame, which 1e9² = 1e18 leaves ~1e20 of room for. Real
// emitters are far below it (the shipped scenes' brightest Ke is 300).
inline constexpr double kMaxMaterialColour = 1e9;

// The check every material colour passes, from an MTL line or a scene file's [[material]]
// override: "" when each component is finite and in [0, kMaxMaterialColour], else what is wrong
// (for "<file:line>: <key>: <problem>").
std::string MaterialColourProblem(const std::vector<double>& components);

// Validates and finishes a mesh: finite positions/normals/uvs, indices in range, one material
// per triangle, unit normals (vertices whose normal is missing or zero get the area-weighted
// average of their faces' normals). Throws fovrt::Error naming `file`.
void FinishMesh(Mesh& mesh, const std::string& file);

}  // namespace fovrt::detail
