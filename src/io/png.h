// 8-bit PNG output for previews and HTML reports; PNG input (8 or 16 bit) for scoring images.
//
// Display transform: scale by 2^exposure (exposure in stops), then either clamp to [0,1]
// (Tonemap::Clamp — the default, identical to src/metrics/tonemap.h's ToneMap at exposure 0) or
// Reinhard x/(1+x) per channel (Tonemap::Reinhard), then the sRGB OETF, then round to 8 bits —
// written once for C++ and GLSL in shaders/common/display_transform.glsl, so the live preview's
// display pass (src/display/display_pass.h) shows the bytes a PNG holds.
// Non-finite and negative values display as 0. PNGs are encoded by stb_image_write, whose
// implementation Debian compiles once into libstb (we link it; nobody defines
// STB_IMAGE_WRITE_IMPLEMENTATION).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "core/image.h"
#include "core/math.h"

namespace fovrt {

enum class Tonemap { Clamp, Reinhard };

// Tonemapped, sRGB-encoded 8-bit RGB bytes (row 0 at the top), 3 bytes per pixel.
std::vector<uint8_t> TonemapToRgb8(const Plane<vec3>& hdr, float exposure = 0.0f,
                                   Tonemap tonemap = Tonemap::Clamp);

// PNG bytes of already-encoded 8-bit RGB data (e.g. an error heat map).
std::vector<uint8_t> EncodeRgb8Png(int width, int height, const std::vector<uint8_t>& rgb);
// PNG bytes of an HDR image after the display transform above (for embedding in HTML reports).
std::vector<uint8_t> EncodePngToMemory(const Plane<vec3>& hdr, float exposure = 0.0f,
                                       Tonemap tonemap = Tonemap::Clamp);

// Writes a PNG atomically (temp + rename).
void WritePng(const std::filesystem::path& path, const Plane<vec3>& hdr, float exposure = 0.0f,
              Tonemap tonemap = Tonemap::Clamp);
void WriteRgb8Png(const std::filesystem::path& path, int width, int height,
                  const std::vector<uint8_t>& rgb);

// Reads an 8- or 16-bit PNG (grey, grey+alpha, RGB or RGBA; alpha ignored) as its encoded values
// in [0,1], no transfer function applied. fovrt::Error naming the file when it cannot be read.
Plane<vec3> ReadPngRgb(const std::filesystem::path& path);

// A PNG's pixels as stored, for a reader that maps code values through a table instead of
// converting each to float: `channels` codes per pixel (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA),
// 8 or 16 bits each, row 0 at the top. Code c of a b-bit image is the value c / (2^b − 1).
struct PngPixels {
    int width = 0, height = 0, channels = 0, bits = 8;
    const uint8_t* bytes() const { return static_cast<const uint8_t*>(data.get()); }    // bits == 8
    const uint16_t* words() const { return static_cast<const uint16_t*>(data.get()); }  // bits == 16
    std::shared_ptr<void> data;  // stb's buffer
};
PngPixels ReadPngPixels(const std::filesystem::path& path);

}  // namespace fovrt
