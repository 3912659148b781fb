// The display composition of the live preview (SPEC §11): what a window shows of a stereo frame.
// Both eyes (linear float RGB, W×H each) go through the display transform that PNG output uses
// (shaders/common/display_transform.glsl: 2^exposure, clamp or Reinhard, sRGB, 8 bits), are
// letterboxed into the window side by side (or one eye enlarged), and get the gaze marker and the
// fovea outline on top. The result is one packed 8-bit pixel per window pixel, in the byte order of
// the swapchain format, ready for vkCmdCopyBufferToImage.
//
// This header is the description every reader shares: the settings, the slot viewports, the push
// constants built from them (MakeDisplayComposePush, the one place the geometry is computed) and
// the C++ reference of the shader (ComposeDisplayReference). The Vulkan host is DisplayPass
// (display/display_pass.h). No Vulkan header here.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "core/image.h"
#include "core/math.h"
#include "io/png.h"
#include "shaders/push_constants.h"

namespace fovrt {

// What the pixels hold.
enum class DisplayMode {
    Hdr,      // radiance: 2^exposure, the tone curve, sRGB (as PNG output)
    Display,  // already display-referred linear [0,1] (false-colour maps): clamp + sRGB only
};
// Where the eyes go.
enum class DisplayLayout {
    SideBySide,  // left eye in the left half, right eye in the right half, each letterboxed
    LeftEye,     // the left eye alone, letterboxed to fill the window
    RightEye,    // the right eye alone
};
// Byte order of the swapchain format the output is copied into (UNORM or SRGB alike: the bytes
// are sRGB-encoded either way, and copies do not convert).
enum class DisplayByteOrder {
    Bgra,  // VK_FORMAT_B8G8R8A8_UNORM / _SRGB (the usual desktop swapchain)
    Rgba,  // VK_FORMAT_R8G8B8A8_UNORM / _SRGB
};

struct DisplaySettings {
    DisplayMode mode = DisplayMode::Hdr;
    float exposure = 0.0f;             // stops (output.exposure); Hdr only
    Tonemap tonemap = Tonemap::Clamp;  // tone curve (io/png.h); Hdr only
    DisplayLayout layout = DisplayLayout::SideBySide;
    bool overlay = true;               // gaze marker and fovea outline
    DisplayByteOrder byteOrder = DisplayByteOrder::Bgra;
};

// One eye's overlay, in that eye's pixels: continuous coordinates (pixel (i, j) covers
// [i, i+1) × [j, j+1), row 0 at the top); the gaze may lie outside the image, and the overlay is
// clipped to the eye's viewport. A non-finite gaze draws nothing; radius ≤ 0 draws no outline.
// With a modelled eye tracker (gaze/tracker.h) the spp map follows the tracked gaze (gazePixel,
// the + and the circle) and the eye is at trueGazePixel (an ×); non-finite: no × (no tracker).
struct FoveaMark {
    vec2 gazePixel{0.0f};
    float foveaRadius = 0.0f;  // eye pixels
    vec2 trueGazePixel{std::numeric_limits<float>::quiet_NaN()};
};

// An eye's place in the window (output pixels). extent 0: not shown.
struct DisplayViewport {
    ivec2 origin{0};
    ivec2 extent{0};
};

// The viewports of slot 0 (the left eye side by side, or the one eye shown) and slot 1 (the right
// eye side by side; empty otherwise) for eyes of eyeSize in a window of outSize. Each keeps the
// eye's aspect ratio (rounded to whole pixels) and is centred in its half (side by side: both
// halves are ⌊outW/2⌋ wide, flush with the window's edges, so an odd width leaves a middle
// column of background) or in the window; what is left is background.
std::array<DisplayViewport, 2> DisplayViewports(DisplayLayout layout, ivec2 eyeSize, ivec2 outSize);

// The push constants of one composition (shaders/push_constants.h, FOVRT_PUSH_DISPLAY_COMPOSE):
// viewports, overlay in fixed-point output pixels, scale = 2^exposure (Hdr) or 1, flags.
// eyeSize (0, 0): no eyes yet, the window is background.
DisplayComposePush MakeDisplayComposePush(const DisplaySettings& settings, ivec2 eyeSize,
                                          const std::array<FoveaMark, 2>& marks, ivec2 outSize);

// The C++ reference of shaders/display_compose.comp: one packed pixel per output pixel, row-major
// (i = y·outW + x), byte order as the push constants say. left and right are W×H alike.
std::vector<uint32_t> ComposeDisplayReference(const Plane<vec3>& left, const Plane<vec3>& right,
                                              const DisplayComposePush& push);
// The same from the settings (MakeDisplayComposePush, then the above).
std::vector<uint32_t> ComposeDisplayReference(const Plane<vec3>& left, const Plane<vec3>& right,
                                              const std::array<FoveaMark, 2>& marks,
                                              const DisplaySettings& settings, int outWidth, int outHeight);

// A packed pixel's colour as 0xRRGGBB (alpha dropped), whichever byte order it was written in.
uint32_t DisplayPixelRgb(uint32_t packed, DisplayByteOrder order);
// Packed pixels as R,G,B bytes (alpha dropped): what WriteRgb8Png takes.
std::vector<uint8_t> DisplayPixelsRgb8(std::span<const uint32_t> packed, DisplayByteOrder order);

}  // namespace fovrt
