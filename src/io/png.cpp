#include "io/png.h"

#include <algorithm>
#include <cmath>

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include "core/atomic_file.h"
#include "core/check.h"
#include "core/error.h"
#include "shaders/common/display_transform.glsl"

namespace fovrt {
namespace {

void AppendBytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    const auto* bytes = static_cast<const uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

std::vector<uint8_t> TonemapToRgb8(const Plane<vec3>& hdr, float exposure, Tonemap tonemap) {
    // The display transform shared with the live preview's shader
    // (shaders/common/display_transform.glsl).
    const float scale = std::exp2(exposure);
    const bool reinhard = tonemap == Tonemap::Reinhard;
    std::vector<uint8_t> rgb(hdr.size() * 3);
    for (size_t i = 0; i < hdr.size(); ++i)
        for (int c = 0; c < 3; ++c)
            rgb[i * 3 + size_t(c)] = uint8_t(glsl::fovrt_display_byte(hdr[i][c], scale, reinhard));
    return rgb;
}

std::vector<uint8_t> EncodeRgb8Png(int width, int height, const std::vector<uint8_t>& rgb) {
    FOVRT_CHECK(width > 0 && height > 0);
    FOVRT_CHECK_OP(rgb.size(), ==, size_t(width) * size_t(height) * 3);
    std::vector<uint8_t> png;
    if (!stbi_write_png_to_func(&AppendBytes, &png, width, height, 3, rgb.data(), width * 3))
        Fail("PNG encoding of a {}x{} image failed", width, height);
    return png;
}

std::vector<uint8_t> EncodePngToMemory(const Plane<vec3>& hdr, float exposure, Tonemap tonemap) {
    return EncodeRgb8Png(hdr.width(), hdr.height(), TonemapToRgb8(hdr, exposure, tonemap));
}

void WriteRgb8Png(const std::filesystem::path& path, int width, int height,
                  const std::vector<uint8_t>& rgb) {
    if (width <= 0 || height <= 0) Fail("cannot write PNG '{}': empty image ({}x{})", path.string(), width, height);
    std::vector<uint8_t> png = EncodeRgb8Png(width, height, rgb);
    WriteTextAtomically(path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

void WritePng(const std::filesystem::path& path, const Plane<vec3>& hdr, float exposure, Tonemap tonemap) {
    WriteRgb8Png(path, hdr.width(), hdr.height(), TonemapToRgb8(hdr, exposure, tonemap));
}

Plane<vec3> ReadPngRgb(const std::filesystem::path& path) {
    int width = 0, height = 0, channels = 0;
    // 16-bit loading keeps 16-bit PNGs exact and widens 8-bit ones (v·257), so v/65535 = v8/255.
    stbi_us* data = stbi_load_16(path.string().c_str(), &width, &height, &channels, 3);
    if (!data) Fail("{}: cannot read PNG ({})", path.string(), stbi_failure_reason());
    Plane<vec3> image(width, height);
    for (size_t i = 0; i < image.size(); ++i)
        image[i] = vec3(data[3 * i], data[3 * i + 1], data[3 * i + 2]) / 65535.0f;
    stbi_image_free(data);
    return image;
}

PngPixels ReadPngPixels(const std::filesystem::path& path) {
    PngPixels p;
    const std::string name = path.string();
    p.bits = stbi_is_16_bit(name.c_str()) ? 16 : 8;
    void* data = p.bits == 16 ? static_cast<void*>(stbi_load_16(name.c_str(), &p.width, &p.height, &p.channels, 0))
                              : static_cast<void*>(stbi_load(name.c_str(), &p.width, &p.height, &p.channels, 0));
    if (!data) Fail("{}: cannot read PNG ({})", name, stbi_failure_reason());
    p.data = std::shared_ptr<void>(data, stbi_image_free);
    return p;
}

}  // namespace fovrt
