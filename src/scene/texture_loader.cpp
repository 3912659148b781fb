// Image files -> linear textures (stb_image; colour textures are decoded from sRGB).
#include <array>
#include <cmath>

#include <stb_image.h>

#include "core/error.h"
#include "core/rng.h"
#include "scene/loaders.h"

namespace fovrt::detail {
namespace {

float SrgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

const std::array<float, 256>& SrgbTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[size_t(i)] = SrgbToLinear(float(i) / 255.0f);
        return t;
    }();
    return table;
}

}  // namespace

Texture TextureFromPixels(const std::string& path, int width, int height, int channels, int bits,
                          const unsigned char* data, bool srgb) {
    Texture texture;
    texture.path = path;
    texture.width = width;
    texture.height = height;
    texture.texels.resize(size_t(width) * size_t(height));
    const auto& table = SrgbTable();
    for (size_t i = 0; i < texture.texels.size(); ++i) {
        float c[4] = {0.0f, 0.0f, 0.0f, 1.0f};
        for (int k = 0; k < channels && k < 4; ++k) {
            size_t at = i * size_t(channels) + size_t(k);
            if (bits == 16) {
                uint16_t v = uint16_t(data[2 * at] | (data[2 * at + 1] << 8));
                float f = float(v) / 65535.0f;
                c[k] = (srgb && k < 3) ? SrgbToLinear(f) : f;
            } else {
                c[k] = (srgb && k < 3) ? table[data[at]] : float(data[at]) / 255.0f;
            }
        }
        // Grey (+alpha) images replicate the grey channel into RGB.
        if (channels <= 2) {
            float a = channels == 2 ? c[1] : 1.0f;
            c[1] = c[2] = c[0];
            c[3] = a;
        }
        texture.texels[i] = vec4(c[0], c[1], c[2], c[3]);
    }
    return texture;
}

Texture PatternTexture(const std::string& name, bool hashed, int cellsX, int cellsY, float a, float b,
                       int texelsPerCell) {
    Texture texture;
    texture.path = name;
    texture.width = cellsX * texelsPerCell;
    texture.height = cellsY * texelsPerCell;
    texture.texels.resize(size_t(texture.width) * size_t(texture.height));
    for (int y = 0; y < texture.height; ++y)
        for (int x = 0; x < texture.width; ++x) {
            const uint32_t cx = uint32_t(x / texelsPerCell), cy = uint32_t(y / texelsPerCell);
            const bool second = hashed ? (HashCombine(HashCombine(0x524f5547u, cx), cy) & 1u) != 0 : ((cx + cy) & 1u) != 0;
            const float v = second ? b : a;
            texture.texels[size_t(y) * size_t(texture.width) + size_t(x)] = vec4(v, v, v, 1.0f);
        }
    return texture;
}

int LoadTextureFile(const std::filesystem::path& file, bool srgb, const std::string& referrer,
                    LoadContext& context) {
    std::string key = file.lexically_normal().string();
    if (auto it = context.textures.find({key, srgb}); it != context.textures.end()) return it->second;
    if (!std::filesystem::is_regular_file(file))
        Fail("{}: texture file {} not found", referrer, file.string());
    context.Read(file);
    Texture texture;
    int width = 0, height = 0, channels = 0;
    if (stbi_is_hdr(file.c_str())) {
        float* pixels = stbi_loadf(file.c_str(), &width, &height, &channels, 4);
        if (!pixels) Fail("{}: cannot decode texture {}: {}", referrer, file.string(), stbi_failure_reason());
        texture.path = key;
        texture.width = width;
        texture.height = height;
        texture.texels.resize(size_t(width) * size_t(height));
        for (size_t i = 0; i < texture.texels.size(); ++i)
            texture.texels[i] = vec4(pixels[4 * i], pixels[4 * i + 1], pixels[4 * i + 2], pixels[4 * i + 3]);
        stbi_image_free(pixels);
    } else {
        unsigned char* pixels = stbi_load(file.c_str(), &width, &height, &channels, 4);
        if (!pixels) Fail("{}: cannot decode texture {}: {}", referrer, file.string(), stbi_failure_reason());
        texture = TextureFromPixels(key, width, height, 4, 8, pixels, srgb);
        stbi_image_free(pixels);
    }
    context.scene.textures.push_back(std::move(texture));
    int index = int(context.scene.textures.size()) - 1;
    context.textures[{key, srgb}] = index;
    return index;
}

}  // namespace fovrt::detail
