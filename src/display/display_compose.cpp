// Geometry and the C++ reference of the display pass (see display_compose.h).
#include "display/display_compose.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/check.h"
#include "shaders/common/display_constants.glsl"
#include "shaders/common/display_transform.glsl"

namespace fovrt {
namespace {

// The largest rectangle of the eye's aspect ratio inside region (whole pixels, rounded to
// nearest, at least 1×1), centred in it.
DisplayViewport Fit(ivec2 regionOrigin, ivec2 region, ivec2 eye) {
    if (region.x <= 0 || region.y <= 0 || eye.x <= 0 || eye.y <= 0) return {};
    const int64_t rw = region.x, rh = region.y, w = eye.x, h = eye.y;
    ivec2 extent;
    if (rw * h <= rh * w) {  // the region is narrower than the eye: full width, bars above and below
        extent = ivec2(int(rw), int(std::clamp<int64_t>((2 * rw * h + w) / (2 * w), 1, rh)));
    } else {  // full height, bars left and right
        extent = ivec2(int(std::clamp<int64_t>((2 * rh * w + h) / (2 * h), 1, rw)), int(rh));
    }
    return {regionOrigin + (region - extent) / 2, extent};
}

// An output coordinate in subpixels, clamped to the range the shader's integers take.
int Subpixels(double outputPixels) {
    const double s = std::round(outputPixels * FOVRT_DISPLAY_SUBPIXELS);
    return int(std::clamp(s, double(-FOVRT_DISPLAY_MAX_COORD), double(FOVRT_DISPLAY_MAX_COORD)));
}

bool Inside(int x, int y, ivec2 origin, ivec2 extent) {
    return x >= origin.x && y >= origin.y && x < origin.x + extent.x && y < origin.y + extent.y;
}

uint32_t DisplayRgb(const vec3& hdr, float scale, bool reinhard) {
    return (glsl::fovrt_display_byte(hdr.r, scale, reinhard) << 16) |
           (glsl::fovrt_display_byte(hdr.g, scale, reinhard) << 8) | glsl::fovrt_display_byte(hdr.b, scale, reinhard);
}

// Whether output pixel (x, y) is on the gaze cross (1), the fovea circle (2) or the true gaze's ×
// (3), else 0. Distances from the pixel's centre in subpixels, integers only, as in the shader.
int OverlayAt(int x, int y, ivec2 gaze, int radius, const ivec2* trueGaze) {
    constexpr int64_t w = FOVRT_DISPLAY_LINE_HALF_WIDTH, arm = FOVRT_DISPLAY_MARKER_ARM;
    if (trueGaze) {
        const int64_t tx = std::abs(int64_t(x) * FOVRT_DISPLAY_SUBPIXELS + FOVRT_DISPLAY_SUBPIXELS / 2 - trueGaze->x);
        const int64_t ty = std::abs(int64_t(y) * FOVRT_DISPLAY_SUBPIXELS + FOVRT_DISPLAY_SUBPIXELS / 2 - trueGaze->y);
        if (std::abs(tx - ty) <= FOVRT_DISPLAY_DIAGONAL_HALF_WIDTH && std::max(tx, ty) <= arm) return 3;
    }
    const int64_t dx = std::abs(int64_t(x) * FOVRT_DISPLAY_SUBPIXELS + FOVRT_DISPLAY_SUBPIXELS / 2 - gaze.x);
    const int64_t dy = std::abs(int64_t(y) * FOVRT_DISPLAY_SUBPIXELS + FOVRT_DISPLAY_SUBPIXELS / 2 - gaze.y);
    if ((dx <= w && dy <= arm) || (dy <= w && dx <= arm)) return 1;
    if (radius <= 0) return 0;
    const int64_t hi = radius + w, lo = std::max<int64_t>(radius - w, 0);
    const int64_t d2 = dx * dx + dy * dy;
    return d2 >= lo * lo && d2 <= hi * hi ? 2 : 0;
}

}  // namespace

std::array<DisplayViewport, 2> DisplayViewports(DisplayLayout layout, ivec2 eyeSize, ivec2 outSize) {
    if (layout != DisplayLayout::SideBySide) return {Fit(ivec2(0), outSize, eyeSize), DisplayViewport{}};
    const int half = outSize.x / 2;
    return {Fit(ivec2(0), ivec2(half, outSize.y), eyeSize),
            Fit(ivec2(outSize.x - half, 0), ivec2(half, outSize.y), eyeSize)};
}

DisplayComposePush MakeDisplayComposePush(const DisplaySettings& settings, ivec2 eyeSize,
                                          const std::array<FoveaMark, 2>& marks, ivec2 outSize) {
    FOVRT_CHECK(outSize.x > 0 && outSize.y > 0);
    FOVRT_CHECK(eyeSize.x >= 0 && eyeSize.y >= 0);
    // Pixel coordinates stay exact in float, and both eyes' floats indexable by a 32-bit int.
    FOVRT_CHECK_OP(std::max(outSize.x, outSize.y), <, 1 << 24);
    FOVRT_CHECK_OP(int64_t(eyeSize.x) * eyeSize.y * 6, <, int64_t(INT32_MAX));
    const auto viewports = DisplayViewports(settings.layout, eyeSize, outSize);
    // The eye each slot shows: slot 0 the left eye unless the right one is shown alone.
    const bool slot0Right = settings.layout == DisplayLayout::RightEye;
    const std::array<const FoveaMark*, 2> slotMarks = {&marks[slot0Right ? 1 : 0], &marks[1]};

    const bool sideBySide = settings.layout == DisplayLayout::SideBySide;
    // Both slots shown have one extent (same eyes, same halves): the shader keeps one.
    if (sideBySide) FOVRT_CHECK(viewports[0].extent == viewports[1].extent);
    const ivec2 extent = viewports[0].extent;

    uint32_t flags = 0;
    if (settings.byteOrder == DisplayByteOrder::Bgra) flags |= DISPLAY_FLAG_BGRA;
    if (settings.mode == DisplayMode::Hdr && settings.tonemap == Tonemap::Reinhard) flags |= DISPLAY_FLAG_REINHARD;
    if (sideBySide) flags |= DISPLAY_FLAG_SIDE_BY_SIDE;
    if (slot0Right) flags |= DISPLAY_FLAG_SLOT0_RIGHT;
    // Eye pixels per output pixel, rounded to float once: the shader and the reference multiply
    // by the same number.
    const float stepX = extent.x > 0 ? float(double(eyeSize.x) / extent.x) : 0.0f;
    const float stepY = extent.y > 0 ? float(double(eyeSize.y) / extent.y) : 0.0f;
    std::array<ivec2, 2> gaze{ivec2(0), ivec2(0)}, trueGaze{ivec2(0), ivec2(0)};
    std::array<int, 2> radius{0, 0};
    for (int s = 0; s < 2; ++s) {
        const DisplayViewport& v = viewports[size_t(s)];
        const FoveaMark& m = *slotMarks[size_t(s)];
        if (!settings.overlay || v.extent.x == 0 || !std::isfinite(m.gazePixel.x) || !std::isfinite(m.gazePixel.y))
            continue;
        flags |= s == 0 ? DISPLAY_FLAG_MARK0 : DISPLAY_FLAG_MARK1;
        // Eye pixels → output pixels: the viewport's scale (equal along both axes up to rounding;
        // the circle uses the horizontal one).
        const double sx = double(v.extent.x) / eyeSize.x, sy = double(v.extent.y) / eyeSize.y;
        gaze[size_t(s)] = ivec2(Subpixels(v.origin.x + double(m.gazePixel.x) * sx),
                                Subpixels(v.origin.y + double(m.gazePixel.y) * sy));
        if (std::isfinite(m.trueGazePixel.x) && std::isfinite(m.trueGazePixel.y)) {
            flags |= s == 0 ? DISPLAY_FLAG_TRUE0 : DISPLAY_FLAG_TRUE1;
            trueGaze[size_t(s)] = ivec2(Subpixels(v.origin.x + double(m.trueGazePixel.x) * sx),
                                        Subpixels(v.origin.y + double(m.trueGazePixel.y) * sy));
        }
        const double r =
            std::isfinite(m.foveaRadius) ? std::round(double(m.foveaRadius) * sx * FOVRT_DISPLAY_SUBPIXELS) : 0.0;
        radius[size_t(s)] = int(std::clamp(r, 0.0, double(FOVRT_DISPLAY_MAX_RADIUS)));
    }
    const float scale = settings.mode == DisplayMode::Hdr ? std::exp2(settings.exposure) : 1.0f;
    DisplayComposePush push{};
    push.out_size = outSize;
    push.eye_size = eyeSize;
    push.extent = extent;
    push.origin0 = viewports[0].origin;
    push.origin1 = viewports[1].origin;
    push.gaze0 = gaze[0];
    push.gaze1 = gaze[1];
    push.true_gaze0 = trueGaze[0];
    push.true_gaze1 = trueGaze[1];
    push.step_x = stepX;
    push.step_y = stepY;
    push.radius0 = radius[0];
    push.radius1 = radius[1];
    push.scale = scale;
    push.flags = flags;
    return push;
}

std::vector<uint32_t> ComposeDisplayReference(const Plane<vec3>& left, const Plane<vec3>& right,
                                              const DisplayComposePush& push) {
    const int outW = push.out_size.x, outH = push.out_size.y;
    FOVRT_CHECK(outW > 0 && outH > 0);
    const ivec2 eye = push.eye_size;
    if (push.extent.x > 0) {
        FOVRT_CHECK(left.width() == eye.x && left.height() == eye.y);
        FOVRT_CHECK(right.width() == eye.x && right.height() == eye.y);
    }
    const bool reinhard = (push.flags & DISPLAY_FLAG_REINHARD) != 0;
    struct Slot {
        bool shown;
        ivec2 origin, gaze;
        int radius;
        bool mark;
        const Plane<vec3>* image;
        bool showTrue;
        ivec2 trueGaze;
    };
    const std::array<Slot, 2> slots = {
        Slot{true, push.origin0, push.gaze0, push.radius0, (push.flags & DISPLAY_FLAG_MARK0) != 0,
             (push.flags & DISPLAY_FLAG_SLOT0_RIGHT) ? &right : &left, (push.flags & DISPLAY_FLAG_TRUE0) != 0,
             push.true_gaze0},
        Slot{(push.flags & DISPLAY_FLAG_SIDE_BY_SIDE) != 0, push.origin1, push.gaze1, push.radius1,
             (push.flags & DISPLAY_FLAG_MARK1) != 0, &right, (push.flags & DISPLAY_FLAG_TRUE1) != 0, push.true_gaze1}};

    std::vector<uint32_t> out(size_t(outW) * size_t(outH));
    for (int y = 0; y < outH; ++y) {
        for (int x = 0; x < outW; ++x) {
            uint32_t rgb = FOVRT_DISPLAY_BACKGROUND_RGB;
            for (const Slot& s : slots) {
                if (!s.shown || !Inside(x, y, s.origin, push.extent)) continue;
                // Nearest eye pixel: the one under the output pixel's centre, (x − origin + ½)·step
                // in float, as the shader computes it.
                const int ex = std::min(int((float(x - s.origin.x) + 0.5f) * push.step_x), eye.x - 1);
                const int ey = std::min(int((float(y - s.origin.y) + 0.5f) * push.step_y), eye.y - 1);
                rgb = DisplayRgb((*s.image)(ex, ey), push.scale, reinhard);
                if (s.mark) {
                    const int on = OverlayAt(x, y, s.gaze, s.radius, s.showTrue ? &s.trueGaze : nullptr);
                    if (on == 1) rgb = FOVRT_DISPLAY_GAZE_RGB;
                    if (on == 2) rgb = FOVRT_DISPLAY_FOVEA_RGB;
                    if (on == 3) rgb = FOVRT_DISPLAY_TRUE_GAZE_RGB;
                }
                break;
            }
            const uint32_t bgra = 0xFF000000u | rgb;
            const uint32_t rgba = 0xFF000000u | ((rgb & 0xFFu) << 16) | (rgb & 0xFF00u) | ((rgb >> 16) & 0xFFu);
            out[size_t(y) * size_t(outW) + size_t(x)] = (push.flags & DISPLAY_FLAG_BGRA) ? bgra : rgba;
        }
    }
    return out;
}

std::vector<uint32_t> ComposeDisplayReference(const Plane<vec3>& left, const Plane<vec3>& right,
                                              const std::array<FoveaMark, 2>& marks,
                                              const DisplaySettings& settings, int outWidth, int outHeight) {
    FOVRT_CHECK(left.width() == right.width() && left.height() == right.height());
    return ComposeDisplayReference(
        left, right,
        MakeDisplayComposePush(settings, ivec2(left.width(), left.height()), marks, ivec2(outWidth, outHeight)));
}

uint32_t DisplayPixelRgb(uint32_t packed, DisplayByteOrder order) {
    if (order == DisplayByteOrder::Bgra) return packed & 0xFFFFFFu;
    return ((packed & 0xFFu) << 16) | (packed & 0xFF00u) | ((packed >> 16) & 0xFFu);
}

std::vector<uint8_t> DisplayPixelsRgb8(std::span<const uint32_t> packed, DisplayByteOrder order) {
    std::vector<uint8_t> rgb(packed.size() * 3);
    for (size_t i = 0; i < packed.size(); ++i) {
        const uint32_t c = DisplayPixelRgb(packed[i], order);
        for (int k = 0; k < 3; ++k) rgb[3 * i + size_t(k)] = uint8_t(c >> (16 - 8 * k));
    }
    return rgb;
}

}  // namespace fovrt
