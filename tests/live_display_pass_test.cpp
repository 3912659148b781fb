// The display pass (src/display/display_pass.h, shaders/display_compose.comp) and its C++ reference:
// closed forms first (the transform's bytes, letterbox geometry, which half each eye lands in,
// exactly which pixels the overlay changes), then the device against the reference over layouts,
// modes, overlay, byte orders and odd sizes, and the copy into a swapchain-format image.
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "display/display_compose.h"
#include "display/display_pass.h"
#include "io/png.h"
#include "shaders/common/display_constants.glsl"
#include "test_support.h"
#include "vk/context.h"
#include "vk/recorder.h"
#include "vk/recorder.h"
#include "vk/vk_check.h"
#include "vk_test_support.h"

using namespace fovrt;

namespace {

constexpr uint32_t kBackground = FOVRT_DISPLAY_BACKGROUND_RGB;
constexpr uint32_t kGazeColour = FOVRT_DISPLAY_GAZE_RGB;
constexpr uint32_t kFoveaColour = FOVRT_DISPLAY_FOVEA_RGB;
constexpr uint32_t kTrueGazeColour = FOVRT_DISPLAY_TRUE_GAZE_RGB;

// The transform written out in double precision from its definition (2^exposure, clamp, sRGB
// OETF, round): the values used below are far from rounding ties, so float must agree exactly.
int ExpectedByte(double hdr, double exposure = 0.0) {
    double v = hdr * std::exp2(exposure);
    if (!std::isfinite(v) || v < 0.0) v = 0.0;
    v = std::min(v, 1.0);
    const double encoded = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
    return int(std::floor(encoded * 255.0 + 0.5));
}

uint32_t Grey(int byte) { return uint32_t(byte) * 0x010101u; }

std::vector<uint32_t> Rgb(const std::vector<uint32_t>& packed, DisplayByteOrder order) {
    std::vector<uint32_t> out(packed.size());
    for (size_t i = 0; i < packed.size(); ++i) out[i] = DisplayPixelRgb(packed[i], order);
    return out;
}

DisplaySettings Settings(DisplayLayout layout, bool overlay = false) {
    DisplaySettings s;
    s.layout = layout;
    s.overlay = overlay;
    return s;
}

// Largest per-channel difference between two packed images of the same byte order (alpha too).
int MaxChannelDiff(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b, size_t* mismatches) {
    int worst = 0;
    *mismatches = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        if (a[i] != b[i]) ++*mismatches;
        for (int c = 0; c < 4; ++c)
            worst = std::max(worst, std::abs(int((a[i] >> (8 * c)) & 0xFFu) - int((b[i] >> (8 * c)) & 0xFFu)));
    }
    return worst;
}

// An eye image exercising the transform: random radiance in [0, 4) (a quarter clips at exposure
// 0) with negative, NaN and infinite pixels sprinkled in.
Plane<vec3> EyeImage(int w, int h, uint64_t seed) {
    Plane<vec3> img = test::RandomImage(w, h, seed, 4.0f);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (size_t i = 0; i < img.size(); i += 7) img[i].g = -img[i].g;
    if (img.size() > 30) {
        img[3].r = nan;
        img[11].b = inf;
        img[29].g = -inf;
    }
    return img;
}

}  // namespace

TEST_CASE("display_compose's bindings are slots 0..count-1, each once", "[live]") {
    std::multiset<int> slots;
#define FOVRT_TEST_SLOT(pass, name, slot, kind, format, variable) slots.insert(slot);
    DISPLAY_COMPOSE_BINDING_LIST(FOVRT_TEST_SLOT)
#undef FOVRT_TEST_SLOT
    CHECK(slots == std::multiset<int>{0, 1});
    CHECK(DISPLAY_COMPOSE_BINDINGS == 2);
}

TEST_CASE("a constant HDR image gives the byte the tonemap + sRGB formula predicts", "[live]") {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    // Spot values worked out by hand as well: 0.18 → 117.65 → 118, 0.5 → 187.52 → 188.
    CHECK(ExpectedByte(0.18) == 118);
    CHECK(ExpectedByte(0.5) == 188);
    for (float v : {0.0f, 0.001f, 0.01f, 0.05f, 0.18f, 0.25f, 0.5f, 0.75f, 0.9f, 1.0f, 2.0f, -1.0f, nan, inf}) {
        INFO("v = " << v);
        const Plane<vec3> eye(5, 3, vec3(v));
        DisplaySettings s = Settings(DisplayLayout::LeftEye);
        const auto out = Rgb(ComposeDisplayReference(eye, eye, {}, s, 5, 3), s.byteOrder);
        CHECK(out[7] == Grey(ExpectedByte(v)));
        s.exposure = -1.0f;  // one stop down halves the radiance
        CHECK(Rgb(ComposeDisplayReference(eye, eye, {}, s, 5, 3), s.byteOrder)[7] == Grey(ExpectedByte(v, -1.0)));
        s.mode = DisplayMode::Display;  // display data: the exposure does not apply
        CHECK(Rgb(ComposeDisplayReference(eye, eye, {}, s, 5, 3), s.byteOrder)[7] == Grey(ExpectedByte(v)));
    }
    // Reinhard x/(1+x): 3 → 0.75; with exposure −1, 1 → 0.5 → 0.333….
    const Plane<vec3> three(2, 2, vec3(3.0f));
    DisplaySettings s = Settings(DisplayLayout::LeftEye);
    s.tonemap = Tonemap::Reinhard;
    CHECK(Rgb(ComposeDisplayReference(three, three, {}, s, 2, 2), s.byteOrder)[0] == Grey(ExpectedByte(0.75)));
    s.mode = DisplayMode::Display;  // the tone curve is for HDR only
    CHECK(Rgb(ComposeDisplayReference(three, three, {}, s, 2, 2), s.byteOrder)[0] == Grey(255));
}

TEST_CASE("the display transform is PNG output's, byte for byte", "[live]") {
    const Plane<vec3> eye = EyeImage(23, 11, 7);
    for (Tonemap tonemap : {Tonemap::Clamp, Tonemap::Reinhard})
        for (float exposure : {0.0f, -1.5f, 2.0f}) {
            DisplaySettings s = Settings(DisplayLayout::RightEye);
            s.tonemap = tonemap;
            s.exposure = exposure;
            s.byteOrder = DisplayByteOrder::Rgba;
            const std::vector<uint8_t> png = TonemapToRgb8(eye, exposure, tonemap);
            const auto out = ComposeDisplayReference(eye, eye, {}, s, eye.width(), eye.height());  // 1:1
            for (size_t i = 0; i < out.size(); ++i) {
                uint8_t rgba[4];
                std::memcpy(rgba, &out[i], 4);
                INFO("pixel " << i);
                REQUIRE((rgba[0] == png[3 * i] && rgba[1] == png[3 * i + 1] && rgba[2] == png[3 * i + 2]));
                REQUIRE(rgba[3] == 255);
            }
        }
}

TEST_CASE("byte order: BGRA and RGBA hold the same colour", "[live]") {
    const Plane<vec3> eye(4, 4, vec3(1.0f, 0.18f, 0.0f));  // 255, 118, 0
    DisplaySettings s = Settings(DisplayLayout::LeftEye);
    s.byteOrder = DisplayByteOrder::Bgra;
    const uint32_t bgra = ComposeDisplayReference(eye, eye, {}, s, 4, 4)[0];
    s.byteOrder = DisplayByteOrder::Rgba;
    const uint32_t rgba = ComposeDisplayReference(eye, eye, {}, s, 4, 4)[0];
    uint8_t b[4], r[4];
    std::memcpy(b, &bgra, 4);
    std::memcpy(r, &rgba, 4);
    CHECK((b[0] == 0 && b[1] == 118 && b[2] == 255 && b[3] == 255));  // B, G, R, A in memory
    CHECK((r[0] == 255 && r[1] == 118 && r[2] == 0 && r[3] == 255));  // R, G, B, A
}

TEST_CASE("letterbox viewports keep the eye's aspect and are centred", "[live]") {
    // Eyes that fill each half exactly.
    auto v = DisplayViewports(DisplayLayout::SideBySide, ivec2(640, 720), ivec2(1280, 720));
    CHECK((v[0].origin == ivec2(0, 0) && v[0].extent == ivec2(640, 720)));
    CHECK((v[1].origin == ivec2(640, 0) && v[1].extent == ivec2(640, 720)));
    // Square eyes in 640×720 halves: full width, 40-pixel bars above and below.
    v = DisplayViewports(DisplayLayout::SideBySide, ivec2(100, 100), ivec2(1280, 720));
    CHECK((v[0].origin == ivec2(0, 40) && v[0].extent == ivec2(640, 640)));
    CHECK((v[1].origin == ivec2(640, 40) && v[1].extent == ivec2(640, 640)));
    // One wide eye (2:1) in a 301×99 window: full height, 198 wide (rounded), centred.
    v = DisplayViewports(DisplayLayout::LeftEye, ivec2(100, 50), ivec2(301, 99));
    CHECK((v[0].origin == ivec2(51, 0) && v[0].extent == ivec2(198, 99)));
    CHECK(v[1].extent == ivec2(0, 0));
    // Odd width side by side: both halves ⌊301/2⌋ = 150 wide, flush with the edges.
    v = DisplayViewports(DisplayLayout::SideBySide, ivec2(10, 10), ivec2(301, 99));
    CHECK((v[0].origin == ivec2(25, 0) && v[0].extent == ivec2(99, 99)));
    CHECK((v[1].origin == ivec2(151 + 25, 0) && v[1].extent == ivec2(99, 99)));
    // No eyes yet: nothing shown.
    v = DisplayViewports(DisplayLayout::SideBySide, ivec2(0, 0), ivec2(64, 64));
    CHECK((v[0].extent == ivec2(0) && v[1].extent == ivec2(0)));
}

TEST_CASE("side by side puts the left eye left and the right eye right; bars are background", "[live]") {
    const Plane<vec3> red(30, 20, vec3(1, 0, 0)), blue(30, 20, vec3(0, 0, 1));
    for (ivec2 out : {ivec2(160, 90), ivec2(97, 61), ivec2(41, 123)}) {
        INFO(out.x << "x" << out.y);
        for (DisplayLayout layout : {DisplayLayout::SideBySide, DisplayLayout::LeftEye, DisplayLayout::RightEye}) {
            const DisplaySettings s = Settings(layout);
            const auto pixels = Rgb(ComposeDisplayReference(red, blue, {}, s, out.x, out.y), s.byteOrder);
            const auto v = DisplayViewports(layout, ivec2(30, 20), out);
            for (int y = 0; y < out.y; ++y)
                for (int x = 0; x < out.x; ++x) {
                    const uint32_t p = pixels[size_t(y) * size_t(out.x) + size_t(x)];
                    auto in = [&](const DisplayViewport& r) {
                        return x >= r.origin.x && y >= r.origin.y && x < r.origin.x + r.extent.x &&
                               y < r.origin.y + r.extent.y;
                    };
                    uint32_t expected = kBackground;
                    if (in(v[0])) expected = layout == DisplayLayout::RightEye ? 0x0000FFu : 0xFF0000u;
                    if (in(v[1])) expected = 0x0000FFu;
                    REQUIRE(p == expected);
                    if (layout == DisplayLayout::SideBySide && p == 0xFF0000u) REQUIRE(x < out.x / 2);
                    if (layout == DisplayLayout::SideBySide && p == 0x0000FFu) REQUIRE(x >= out.x - out.x / 2);
                }
            // The viewports keep the 3:2 aspect to within a pixel's rounding.
            CHECK(std::abs(v[0].extent.x * 20 - v[0].extent.y * 30) <= 30);
        }
    }
}

TEST_CASE("the overlay changes exactly the pixels on the gaze cross and fovea circle", "[live]") {
    // 1:1 (one eye, window = eye) so the closed form is in eye pixels; the gaze and radius are
    // multiples of 1/8 px, so the fixed point is exact and the test below is the definition:
    // cross: |dx| ≤ 0.75 and |dy| ≤ 6 (or the transpose); circle: r − 0.75 ≤ |d| ≤ r + 0.75,
    // d from the pixel centre.
    const Plane<vec3> eye = test::RandomImage(96, 80, 3, 0.9f);
    for (vec2 gaze : {vec2(40.5f, 30.25f), vec2(-5.0f, 70.0f), vec2(95.875f, 0.125f)}) {
        const float radius = 17.375f;
        INFO("gaze " << gaze.x << "," << gaze.y);
        DisplaySettings s = Settings(DisplayLayout::LeftEye, false);
        const auto off = Rgb(ComposeDisplayReference(eye, eye, {FoveaMark{gaze, radius}, {}}, s, 96, 80), s.byteOrder);
        s.overlay = true;
        const auto on = Rgb(ComposeDisplayReference(eye, eye, {FoveaMark{gaze, radius}, {}}, s, 96, 80), s.byteOrder);
        size_t cross = 0, circle = 0;
        for (int y = 0; y < 80; ++y)
            for (int x = 0; x < 96; ++x) {
                const size_t i = size_t(y) * 96 + size_t(x);
                const double dx = std::abs(x + 0.5 - gaze.x), dy = std::abs(y + 0.5 - gaze.y);
                const double d2 = dx * dx + dy * dy;
                const bool onCross = (dx <= 0.75 && dy <= 6.0) || (dy <= 0.75 && dx <= 6.0);
                const bool onCircle = d2 >= (radius - 0.75) * (radius - 0.75) && d2 <= (radius + 0.75) * (radius + 0.75);
                INFO(x << "," << y);
                if (onCross) {
                    REQUIRE(on[i] == kGazeColour);
                    ++cross;
                } else if (onCircle) {
                    REQUIRE(on[i] == kFoveaColour);
                    ++circle;
                } else {
                    REQUIRE(on[i] == off[i]);
                }
            }
        if (gaze == vec2(40.5f, 30.25f)) {
            // The vertical arm is 1 px wide (x = 40.5 is a pixel centre) and 12 long; the horizontal
            // one 2 px wide (y = 30.25: rows 29 and 30 are within 0.75) and 13 long; 2 shared.
            // The circle, ~1.5 px wide: about 2π·17.4·1.5 ≈ 164 pixels.
            CHECK(cross == 12 + 2 * 13 - 2);
            CHECK(circle > 130);
            CHECK(circle < 200);
        }
    }
}

TEST_CASE("a tracker's true gaze adds an x over the tracked gaze's marker, and only then", "[live]") {
    // 1:1 as above. ×: |dx − dy| ≤ 1 px (8 subpixels) and max(|dx|, |dy|) ≤ 6, drawn over the +
    // and the circle; every other pixel is the overlay without a true gaze.
    const Plane<vec3> eye = test::RandomImage(96, 80, 5, 0.9f);
    const vec2 tracked(40.5f, 30.25f), truth(46.0f, 33.5f);
    const float radius = 17.375f;
    DisplaySettings s = Settings(DisplayLayout::LeftEye, true);
    const auto plain = Rgb(ComposeDisplayReference(eye, eye, {FoveaMark{tracked, radius}, {}}, s, 96, 80), s.byteOrder);
    const auto both =
        Rgb(ComposeDisplayReference(eye, eye, {FoveaMark{tracked, radius, truth}, {}}, s, 96, 80), s.byteOrder);
    size_t onX = 0;
    for (int y = 0; y < 80; ++y)
        for (int x = 0; x < 96; ++x) {
            const size_t i = size_t(y) * 96 + size_t(x);
            const double dx = std::abs(x + 0.5 - truth.x), dy = std::abs(y + 0.5 - truth.y);
            INFO(x << "," << y);
            if (std::abs(dx - dy) <= 1.0 && std::max(dx, dy) <= 6.0) {
                REQUIRE(both[i] == kTrueGazeColour);
                ++onX;
            } else {
                REQUIRE(both[i] == plain[i]);
            }
        }
    // Centre (46, 33.5): dx takes half-pixel steps, dy whole ones, so each diagonal pixel has a
    // neighbour within 1 px: 46 pixels (counted from the closed form).
    CHECK(onX == 46);
    // Without the overlay, nothing of either.
    s.overlay = false;
    CHECK(Rgb(ComposeDisplayReference(eye, eye, {FoveaMark{tracked, radius, truth}, {}}, s, 96, 80), s.byteOrder) ==
          Rgb(ComposeDisplayReference(eye, eye, {FoveaMark{tracked, radius}, {}}, s, 96, 80), s.byteOrder));
}

TEST_CASE("the overlay stays inside its eye's viewport, scaled with it", "[live]") {
    // Side by side, letterboxed and scaled ×2: the left eye's circle reaching past its half does not
    // touch the right half or the bars, and its gaze cross sits where the gaze lands.
    const Plane<vec3> left(40, 30, vec3(0.5f)), right(40, 30, vec3(0.25f));
    const std::array<FoveaMark, 2> marks = {FoveaMark{vec2(39.0f, 15.0f), 10.0f}, FoveaMark{vec2(-100.0f, 0.0f), 5.0f}};
    DisplaySettings s = Settings(DisplayLayout::SideBySide, false);
    const auto off = Rgb(ComposeDisplayReference(left, right, marks, s, 160, 80), s.byteOrder);
    s.overlay = true;
    const auto on = Rgb(ComposeDisplayReference(left, right, marks, s, 160, 80), s.byteOrder);
    const auto v = DisplayViewports(s.layout, ivec2(40, 30), ivec2(160, 80));
    REQUIRE((v[0].origin == ivec2(0, 10) && v[0].extent == ivec2(80, 60)));
    size_t changed = 0;
    for (int y = 0; y < 80; ++y)
        for (int x = 0; x < 160; ++x) {
            const size_t i = size_t(y) * 160 + size_t(x);
            if (on[i] == off[i]) continue;
            ++changed;
            INFO(x << "," << y);
            REQUIRE(x < 80);  // the right eye's gaze is far outside its image: nothing drawn there
            REQUIRE((y >= 10 && y < 70));
        }
    CHECK(changed > 50);
    // Gaze (39, 15) → output (78, 40): the cross's centre pixel.
    CHECK(on[40 * 160 + 77] == kGazeColour);
    // A non-finite gaze draws nothing.
    const std::array<FoveaMark, 2> none = {FoveaMark{vec2(std::numeric_limits<float>::quiet_NaN()), 10.0f}, FoveaMark{}};
    CHECK(Rgb(ComposeDisplayReference(left, right, none, Settings(DisplayLayout::LeftEye, true), 50, 50), s.byteOrder) ==
          Rgb(ComposeDisplayReference(left, right, none, Settings(DisplayLayout::LeftEye, false), 50, 50), s.byteOrder));
}

TEST_CASE("display pass on Vulkan equals the C++ reference", "[live][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto ctx = test::TestContext();
    INFO("device: " << ctx->deviceName() << ", validation " << ctx->validationEnabled());
    DisplayPass pass(*ctx);
    // Before any eyes: background only.
    for (uint32_t p : pass.Run(DisplaySettings{}, 7, 5)) REQUIRE(p == (0xFF000000u | kBackground));

    struct Case {
        ivec2 eye, out;
    };
    // Non-square and odd sizes; upscaled, downscaled, 1:1, a window narrower than its halves.
    const std::array<Case, 4> cases = {Case{{64, 48}, {97, 61}}, Case{{33, 17}, {128, 40}}, Case{{50, 30}, {50, 30}},
                                       Case{{40, 40}, {23, 71}}};
    size_t compared = 0, mismatched = 0;
    int worst = 0;
    for (const Case& c : cases) {
        const Plane<vec3> left = EyeImage(c.eye.x, c.eye.y, 11), right = EyeImage(c.eye.x, c.eye.y, 12);
        const std::array<FoveaMark, 2> marks = {FoveaMark{vec2(c.eye) * 0.4f, 0.3f * float(c.eye.y)},
                                                FoveaMark{vec2(c.eye) * vec2(0.7f, 0.55f), 0.2f * float(c.eye.x),
                                                          vec2(c.eye) * vec2(0.6f, 0.5f)}};  // a tracker's true gaze
        pass.SetEyes(left, right, marks);
        for (DisplayLayout layout : {DisplayLayout::SideBySide, DisplayLayout::LeftEye, DisplayLayout::RightEye})
            for (int mode = 0; mode < 3; ++mode)  // HDR clamp, HDR Reinhard with exposure, display data
                for (bool overlay : {false, true})
                    for (DisplayByteOrder order : {DisplayByteOrder::Bgra, DisplayByteOrder::Rgba}) {
                        DisplaySettings s;
                        s.layout = layout;
                        s.mode = mode == 2 ? DisplayMode::Display : DisplayMode::Hdr;
                        s.tonemap = mode == 1 ? Tonemap::Reinhard : Tonemap::Clamp;
                        s.exposure = mode == 1 ? 0.7f : 0.0f;
                        s.overlay = overlay;
                        s.byteOrder = order;
                        INFO("eye " << c.eye.x << "x" << c.eye.y << " out " << c.out.x << "x" << c.out.y << " layout "
                                    << int(layout) << " mode " << mode << " overlay " << overlay << " order " << int(order));
                        const auto device = pass.Run(s, c.out.x, c.out.y);
                        const auto reference = ComposeDisplayReference(left, right, marks, s, c.out.x, c.out.y);
                        REQUIRE(device.size() == reference.size());
                        size_t m = 0;
                        const int diff = MaxChannelDiff(device, reference, &m);
                        CHECK(diff <= 1);  // pow and division: a few ULP on the device
                        worst = std::max(worst, diff);
                        mismatched += m;
                        compared += device.size();
                    }
    }
    WARN("display pass: " << mismatched << " of " << compared << " pixels differ from the reference (max "
                          << worst << " LSB) on " << ctx->deviceName() << ", validation "
                          << (ctx->validationEnabled() ? "on" : "off"));
    CHECK(mismatched * 100 <= compared);  // off-by-one bytes are rare, not the rule
    CHECK(ctx->validationErrors() == 0);
}

TEST_CASE("display pass on Vulkan: constant HDR gives the formula's byte, 1:1 gives PNG's bytes", "[live][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto ctx = test::TestContext();
    DisplayPass pass(*ctx);
    for (float v : {0.001f, 0.05f, 0.18f, 0.5f, 0.9f, 3.0f, -2.0f}) {
        INFO("v = " << v);
        const Plane<vec3> eye(8, 6, vec3(v));
        pass.SetEyes(eye, eye, {});
        DisplaySettings s = Settings(DisplayLayout::SideBySide);
        for (uint32_t p : Rgb(pass.Run(s, 16, 6), s.byteOrder)) REQUIRE(p == Grey(ExpectedByte(v)));
    }
    const Plane<vec3> eye = EyeImage(37, 21, 5);
    pass.SetEyes(eye, eye, {});
    DisplaySettings s = Settings(DisplayLayout::LeftEye);
    s.byteOrder = DisplayByteOrder::Rgba;
    s.exposure = -0.5f;
    const auto device = pass.Run(s, 37, 21);
    const std::vector<uint8_t> png = TonemapToRgb8(eye, s.exposure);
    int worst = 0;
    for (size_t i = 0; i < device.size(); ++i)
        for (int c = 0; c < 3; ++c)
            worst = std::max(worst, std::abs(int((device[i] >> (8 * c)) & 0xFFu) - int(png[3 * i + size_t(c)])));
    CHECK(worst <= 1);
    CHECK(ctx->validationErrors() == 0);
}

namespace {

// A colour image as a swapchain would have it, with its memory (the test's own, minimal).
struct TestImage {
    VkDevice device = VK_NULL_HANDLE;
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    TestImage(VulkanContext& ctx, VkFormat format, ivec2 size) : device(ctx.device()) {
        auto info = VkInit<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
        info.imageType = VK_IMAGE_TYPE_2D;
        info.format = format;
        info.extent = {uint32_t(size.x), uint32_t(size.y), 1};
        info.mipLevels = 1;
        info.arrayLayers = 1;
        info.samples = VK_SAMPLE_COUNT_1_BIT;
        info.tiling = VK_IMAGE_TILING_OPTIMAL;
        info.usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
        info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        FOVRT_VK(vkCreateImage(device, &info, nullptr, &image));
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(device, image, &req);
        VkPhysicalDeviceMemoryProperties props;
        vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &props);
        uint32_t type = 0;
        while (!(req.memoryTypeBits & (1u << type))) ++type;
        auto alloc = VkInit<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
        alloc.allocationSize = req.size;
        alloc.memoryTypeIndex = type;
        FOVRT_VK(vkAllocateMemory(device, &alloc, nullptr, &memory));
        FOVRT_VK(vkBindImageMemory(device, image, memory, 0));
    }
    ~TestImage() {
        vkDestroyImage(device, image, nullptr);
        vkFreeMemory(device, memory, nullptr);
    }
    TestImage(const TestImage&) = delete;
    TestImage& operator=(const TestImage&) = delete;
};

// A transfer-to-transfer layout transition.
void Transition(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags srcAccess,
                VkAccessFlags dstAccess) {
    RecordImageBarrier(cmd, image, from, to, srcAccess, dstAccess, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT);
}

}  // namespace

TEST_CASE("Record in the caller's command buffer, then a copy into a swapchain-format image", "[live][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto ctx = test::TestContext();
    const ivec2 out(75, 42);
    DisplayPass pass(*ctx);
    const Plane<vec3> left = EyeImage(31, 24, 21), right = EyeImage(31, 24, 22);
    const std::array<FoveaMark, 2> marks = {FoveaMark{vec2(10.0f, 12.0f), 6.0f}, FoveaMark{vec2(20.0f, 5.0f), 4.0f}};
    // UNORM and SRGB formats of both byte orders receive the same bytes: copies do not convert.
    const std::array<std::pair<VkFormat, DisplayByteOrder>, 4> formats = {
        std::pair{VK_FORMAT_B8G8R8A8_UNORM, DisplayByteOrder::Bgra},
        std::pair{VK_FORMAT_B8G8R8A8_SRGB, DisplayByteOrder::Bgra},
        std::pair{VK_FORMAT_R8G8B8A8_UNORM, DisplayByteOrder::Rgba},
        std::pair{VK_FORMAT_R8G8B8A8_SRGB, DisplayByteOrder::Rgba}};
    for (const auto& [format, order] : formats) {
        INFO("format " << int(format));
        DisplaySettings s;
        s.byteOrder = order;
        pass.SetEyes(left, right, marks);
        TestImage image(*ctx, format, out);
        Buffer readback =
            ctx->allocator().CreateBuffer("test.readback", size_t(out.x) * size_t(out.y) * 4, MemoryUsage::Staging);
        {
            CommandRecorder recorder(*ctx);
            VkCommandBuffer cmd = recorder.commandBuffer();
            pass.Record(cmd, s, out.x, out.y);  // as a window thread would, then its own copy
            Transition(cmd, image.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                       VK_ACCESS_TRANSFER_WRITE_BIT);
            const VkBufferImageCopy region = pass.OutputCopyRegion();
            vkCmdCopyBufferToImage(cmd, pass.Output().handle(), image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                                   &region);
            Transition(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                       VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT);
            vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.handle(), 1, &region);
            recorder.Barrier();  // transfer write → host read
            recorder.Submit();
        }
        std::vector<uint32_t> pixels(size_t(out.x) * size_t(out.y));
        std::memcpy(pixels.data(), readback.mapped(), pixels.size() * 4);
        size_t m = 0;
        CHECK(MaxChannelDiff(pixels, ComposeDisplayReference(left, right, marks, s, out.x, out.y), &m) <= 1);
        // Twice in a row with no new eyes (no upload): the same picture.
        CHECK(pass.Run(s, out.x, out.y) == pixels);
    }
    CHECK(ctx->validationErrors() == 0);
}

TEST_CASE("display pass resizes with the window and the eyes", "[live][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto ctx = test::TestContext();
    DisplayPass pass(*ctx);
    for (ivec2 eye : {ivec2(16, 16), ivec2(45, 20), ivec2(16, 16)}) {
        const Plane<vec3> left = EyeImage(eye.x, eye.y, 1), right = EyeImage(eye.x, eye.y, 2);
        pass.SetEyes(left, right, {});
        for (ivec2 out : {ivec2(64, 64), ivec2(129, 33), ivec2(1, 1), ivec2(64, 64)}) {
            const DisplaySettings s;
            size_t m = 0;
            const auto reference = ComposeDisplayReference(left, right, {}, s, out.x, out.y);
            CHECK(MaxChannelDiff(pass.Run(s, out.x, out.y), reference, &m) <= 1);
            CHECK(pass.outputSize() == out);
            CHECK(pass.Output().size() == size_t(out.x) * size_t(out.y) * 4);
        }
    }
    CHECK(ctx->validationErrors() == 0);
}

TEST_CASE("display bench measures a composition", "[live][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto ctx = test::TestContext();
    const DisplayBenchResult r = BenchDisplayPass(*ctx, ivec2(64, 36), ivec2(32, 36), 2);
    CHECK(r.submitMs > 0.0);
    if (r.timestamps) CHECK(r.uploadComposeMs > 0.0);
    CHECK(FormatDisplayBench(r).find("display compose 64x36") != std::string::npos);
    CHECK(ctx->validationErrors() == 0);
}

// Not run by default: `live_display_pass_test "[.bench]"` prints the cost at 1280×720.
TEST_CASE("display bench at 1280x720", "[.bench][live][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto ctx = test::TestContext();
    WARN(FormatDisplayBench(BenchDisplayPass(*ctx)));
    WARN(FormatDisplayBench(BenchDisplayPass(*ctx, ivec2(1280, 720), ivec2(1280, 720))));
    CHECK(ctx->validationErrors() == 0);
}
