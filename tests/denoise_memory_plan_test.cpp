// The memory plan (denoise/memory_plan.h): staging as large as the transfers need, every
// variant's bytes per pixel at headset size held (a change that grows one fails here), the
// budget checked against the peak, and how fp16 storage holds the colour inputs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/packing.hpp>

#include "denoise/gradient_strata.h"
#include "denoise/memory_plan.h"
#include "denoise/pass_plan.h"
#include "denoise/planes.h"
#include "denoise/variants.h"

using namespace fovrt;

namespace {
size_t Bytes(const DenoiserPlan& plan, const std::string& name) {
    for (const BufferPlan& b : plan.buffers)
        if (b.name == name) return b.bytes;
    return 0;
}
}  // namespace

TEST_CASE("staging is the transfer ring: the frame's transfers when they fit, else the ring's size") {
    const int w = 40, h = 24;
    const size_t pixels = size_t(w) * size_t(h);
    // Every frame uploads direct, indirect, modulation, emission (4 × 12 B), the depth gradient and
    // the previous pixel (2 × 8 B), this frame's normal, depth and object id (12 + 4 + 4 B), then
    // downloads the 12 B output and the 8 B counters (aligned to 16).
    const size_t every = pixels * (4 * 12 + 2 * 8 + 12 + 4 + 4) + pixels * 12 + 16;
    const size_t counts = StagingAlign(PlaneBytes(PlaneKind::SampleCount, {w, h}));
    const size_t samples = StagingAlign(GradientSampleCapacity(w, h) * sizeof(GradientSample));
    CHECK(Bytes(BuildDenoiserPlan("svgf", DenoiserParams{}, w, h), "staging") == every);
    // Only what a variant uploads: the sample counts where it reads them, A-SVGF's gradient
    // samples where it reads those.
    CHECK(Bytes(BuildDenoiserPlan("two-history", DenoiserParams{}, w, h), "staging") == every + counts);
    CHECK(Bytes(BuildDenoiserPlan("two-history-asvgf", DenoiserParams{}, w, h), "staging") ==
          every + counts + samples);
    DenoiserParams small;
    small.transferRingBytes = 4096;
    for (const char* name : {"svgf", "two-history-asvgf"})
        CHECK(Bytes(BuildDenoiserPlan(name, small, w, h), "staging") == 4096);
    // At a headset's size the default ring is a few bytes per pixel, whatever the variant.
    const DenoiserPlan headset = BuildDenoiserPlan("two-history", DenoiserParams{}, 2064, 2208);
    CHECK(Bytes(headset, "staging") == DenoiserParams{}.transferRingBytes);
}

// `fovrt memory --width 2064 --height 2208 --eyes 2 --denoiser NAME --precision fp32|fp16` (the
// default parameters), in bytes per pixel: the peak of one eye (permanent buffers and transient
// pool), and of both eyes on one device, which take turns with one transient pool and staging
// ring (AddDenoiserOnDevice), over the two eyes' pixels. #40's goals in fp16, both eyes:
// two-history at most 170 B/pixel (1.5 GiB), svgf at most 1 GiB. The RAE keeps buffers of its own.
TEST_CASE("every variant's bytes per pixel at headset size (2064x2208) hold, per eye and for both eyes") {
    struct Expected {
        double eyeFp32, eyeFp16, bothFp32, bothFp16;
    };
    const std::map<std::string, Expected> expected = {
        {"svgf", {263.68, 151.68, 199.84, 107.84}},
        {"svgf-weighted", {281.68, 161.68, 216.84, 116.84}},
        {"asvgf", {277.01, 169.01, 213.17, 125.17}},
        {"two-history", {403.68, 219.68, 309.84, 161.84}},
        {"two-history-asvgf", {417.01, 237.01, 323.17, 179.17}},
        {"asvgf-antilag", {277.01, 169.01, 213.17, 125.17}},
        {"two-history-asvgf-antilag", {417.01, 237.01, 323.17, 179.17}},
        {"two-history-stable", {427.68, 235.68, 329.84, 173.84}},
        {"two-history-stable-firefly", {427.68, 235.68, 329.84, 173.84}},
        {"two-history-stable-antilag", {427.68, 235.68, 329.84, 173.84}},
        {"two-history-asvgf-stable-antilag", {441.01, 253.01, 343.17, 191.17}},
        {"two-history-clamp", {403.68, 219.68, 309.84, 161.84}},
        {"two-history-stable-clamp", {427.68, 235.68, 329.84, 173.84}},
        {"two-history-hysteresis", {419.68, 231.68, 321.84, 169.84}},
        {"two-history-stable-hysteresis", {435.68, 239.68, 337.84, 177.84}},
        {"two-history-asvgf-stable-hysteresis", {449.01, 257.01, 351.17, 195.17}},
        {"rae", {395.86, 199.83, 395.86, 199.83}},
        {"rae-spp", {399.89, 201.84, 399.89, 201.84}},
    };
    const int w = 2064, h = 2208;
    const double pixels = double(w) * double(h);
    std::map<std::string, size_t> bothFp16Bytes;
    for (const std::string& name : DenoiserNames()) {
        INFO(name);
        REQUIRE(expected.count(name) == 1);
        const Expected& e = expected.at(name);
        for (Precision precision : {Precision::Fp32, Precision::Fp16}) {
            DenoiserParams params;
            params.precision = precision;
            const std::vector<BufferPlan> eye = BuildDenoiserPlan(name, params, w, h).buffers;
            std::vector<BufferPlan> device;
            for (const char* prefix : {"eye0.", "eye1."}) AddDenoiserOnDevice(device, prefix, eye);
            const bool fp16 = precision == Precision::Fp16;
            const double perEye = double(TotalBytes(eye)) / pixels, both = double(TotalBytes(device)) / (2.0 * pixels);
            if (fp16) bothFp16Bytes[name] = TotalBytes(device);
            std::printf("%-40s %s %8.2f B/pixel per eye, %8.2f both eyes\n", name.c_str(), fp16 ? "fp16" : "fp32",
                        perEye, both);
            CHECK(perEye == Approx(fp16 ? e.eyeFp16 : e.eyeFp32).margin(0.01));
            CHECK(both == Approx(fp16 ? e.bothFp16 : e.bothFp32).margin(0.01));
        }
    }
    const double GiB = 1024.0 * 1024.0 * 1024.0;
    CHECK(double(bothFp16Bytes.at("two-history")) / (2.0 * pixels) <= 170.0);
    CHECK(double(bothFp16Bytes.at("two-history")) <= 1.5 * GiB);
    CHECK(double(bothFp16Bytes.at("svgf")) <= 1.0 * GiB);
}

// The weighted history's window (denoise/history_window.h): its size and place in closed form, and
// the bytes it saves, which are the weighted planes' 40 B/pixel in fp16 (W_w, S_k and I_w per
// channel, A and B) outside the window.
TEST_CASE("the weighted history's window: its size, its place, and the history bytes it keeps") {
    CHECK(WeightedWindowSize(64, 64, 0.5f) == ivec2(32, 32));
    CHECK(WeightedWindowSize(67, 45, 0.5f) == ivec2(34, 23));  // ⌈33.5⌉, ⌈22.5⌉
    CHECK(WeightedWindowSize(2064, 2208, 1.0f) == ivec2(2064, 2208));
    CHECK(WeightedWindowSize(2064, 2208, 0.5f) == ivec2(1032, 1104));
    CHECK(WeightedWindowSize(10, 10, 1e-6f) == ivec2(1, 1));
    CHECK(WeightedWindowAt(64, 64, 0.5f, std::nullopt).origin == ivec2(16, 16));  // no gaze: the centre
    CHECK(WeightedWindowAt(64, 64, 0.5f, vec2(20.5f, 30.0f)).origin == ivec2(5, 14));  // ⌊c − 16 + ½⌋
    CHECK(WeightedWindowAt(64, 64, 0.5f, vec2(-40.0f, 2.0f)).origin == ivec2(0, 0));  // kept inside
    CHECK(WeightedWindowAt(64, 64, 0.5f, vec2(63.9f, 100.0f)).origin == ivec2(32, 32));
    const HistoryWindow w = WeightedWindowAt(64, 64, 0.5f, vec2(20.5f, 30.0f));
    CHECK(w.Index(5, 14) == 0);
    CHECK(w.Index(36, 45) == 31 * 32 + 31);
    CHECK(w.Index(4, 14) == -1);
    CHECK(w.Index(37, 20) == -1);

    const int width = 2064, height = 2208;
    const double pixels = double(width) * double(height);
    auto historyBytes = [&](float window) {
        DenoiserParams params;
        params.precision = Precision::Fp16;
        params.twoHistory.window = window;
        size_t bytes = 0;
        for (const BufferPlan& b : BuildDenoiserPlan("two-history", params, width, height).buffers)
            bytes += b.history ? b.bytes : 0;
        return double(bytes) / pixels;
    };
    CHECK(historyBytes(1.0f) == Approx(104.0));
    for (float window : {0.75f, 0.5f, 0.25f}) {
        const ivec2 size = WeightedWindowSize(width, height, window);
        INFO("window " << window);
        CHECK(historyBytes(window) == Approx(64.0 + 40.0 * double(size.x) * double(size.y) / pixels));
    }
    // svgf keeps no weighted history: the setting leaves its plan alone.
    DenoiserParams params;
    params.twoHistory.window = 0.25f;
    CHECK(TotalBytes(BuildDenoiserPlan("svgf", params, width, height).buffers) ==
          TotalBytes(BuildDenoiserPlan("svgf", DenoiserParams{}, width, height).buffers));
}

TEST_CASE("the budget is checked against the peak: a transient slot counts once, not per plane it holds") {
    const DenoiserPlan plan = BuildDenoiserPlan("two-history", DenoiserParams{}, 64, 64);
    size_t planes = 0;
    for (const PlanePlacement& p : plan.planes) planes += p.bytes;
    const size_t peak = TotalBytes(plan.buffers);
    CHECK(peak < planes);
    CHECK(TransientBytes(plan.buffers) > 0);
    CHECK_NOTHROW(EnforceMemoryBudget(plan.buffers, peak));
    CHECK_THROWS_WITH(EnforceMemoryBudget(plan.buffers, peak - 1), Catch::Contains(std::to_string(peak)));
}

// fp16 storage uploads the colour inputs as RGBA16F: 8 bytes per pixel instead of 12, rounded to
// the nearest half, finite values saturated at ±65000, NaN and ±inf kept for the shaders'
// sanitising to count. The C++ reference rounds its copy of the inputs with the same function.
TEST_CASE("fp16 storage: the colour inputs are RGBA16F, rounded as the reference rounds them") {
    for (PlaneKind kind : {PlaneKind::Direct, PlaneKind::Indirect, PlaneKind::Modulation, PlaneKind::Emission}) {
        CHECK(PlaneElementBytes(kind, Precision::Fp32) == 12);
        CHECK(PlaneElementBytes(kind, Precision::Fp16) == 8);
        CHECK(ConvertedOnUpload(kind, Precision::Fp16));
        CHECK_FALSE(ConvertedOnUpload(kind, Precision::Fp32));
    }
    for (PlaneKind kind : {PlaneKind::ObjectId, PlaneKind::DepthGradient, PlaneKind::PrevPixel, PlaneKind::Guide})
        CHECK_FALSE(ConvertedOnUpload(kind, Precision::Fp16));
    CHECK(QuantizeInput(1.0f) == 1.0f);
    CHECK(QuantizeInput(-2.5f) == -2.5f);
    CHECK(QuantizeInput(0.1f) == 0.0999755859375f);      // the nearest half: 1638·2⁻¹⁴
    CHECK(QuantizeInput(1e6f) == 64992.0f);              // saturated at 65000, then rounded (spacing 32)
    CHECK(QuantizeInput(-1e6f) == -64992.0f);
    CHECK(QuantizeInput(0x1p-24f) == 0x1p-24f);         // the smallest subnormal half is kept
    CHECK(QuantizeInput(0x1p-26f) == 0.0f);             // a quarter of it rounds to 0
    CHECK(std::isinf(QuantizeInput(INFINITY)));
    CHECK(QuantizeInput(-INFINITY) < 0.0f);
    CHECK(std::isnan(QuantizeInput(NAN)));
    const std::vector<vec3> rgb = {vec3(1.0f, 0.1f, 1e6f), vec3(NAN, INFINITY, -0.5f)};
    FrameInputs in;
    in.Allocate(2, 1);
    for (size_t i = 0; i < rgb.size(); ++i) in.direct[i] = rgb[i];
    std::vector<uint16_t> rgba;
    ConvertForUpload(PlaneKind::Direct, in, rgba);
    REQUIRE(rgba.size() == 8);
    for (size_t i = 0; i < rgb.size(); ++i) {
        CHECK(rgba[4 * i + 3] == 0);
        for (int c = 0; c < 3; ++c) {
            const float stored = glm::unpackHalf1x16(rgba[4 * i + size_t(c)]);
            const float rounded = QuantizeInput(rgb[i][c]);
            CHECK((stored == rounded || (std::isnan(stored) && std::isnan(rounded))));
        }
    }
}

// fp16 storage keeps the geometry's normals octahedral: two int16 per pixel, 4 bytes instead of
// 12. The axes and the background's zero normal survive exactly; any unit normal within 1e-4 rad
// (the 16-bit grid's spacing on the octahedron is 2/32767).
TEST_CASE("fp16 storage: normals are octahedral codes, decoded as the shaders decode them") {
    CHECK(PlaneElementBytes(PlaneKind::Normal, Precision::Fp32) == 12);
    CHECK(PlaneElementBytes(PlaneKind::Normal, Precision::Fp16) == 4);
    CHECK(ConvertedOnUpload(PlaneKind::Normal, Precision::Fp16));
    CHECK_FALSE(ConvertedOnUpload(PlaneKind::Normal, Precision::Fp32));
    for (const vec3& axis : {vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1)})
        CHECK(QuantizeNormal(axis) == axis);
    CHECK(OctahedralCode(vec3(0.0f)) == ivec2(-32768, -32768));
    CHECK(QuantizeNormal(vec3(0.0f)) == vec3(0.0f));
    CHECK(QuantizeNormal(vec3(NAN, 0.0f, 1.0f)) == vec3(0.0f));
    CHECK(OctahedralCode(vec3(0, 0, -1)) == ivec2(32767, 32767));  // the lower pole at a corner
    // A reset fills the normal planes with the "no normal" code in fp16, as with 0.0f in fp32.
    const uint32_t cleared = ClearValue(PlaneKind::Normal, Precision::Fp16);
    CHECK(ivec2(int16_t(cleared & 0xFFFFu), int16_t(cleared >> 16)) == OctahedralCode(vec3(0.0f)));
    CHECK(ClearValue(PlaneKind::Normal, Precision::Fp32) == 0u);
    uint32_t state = 12345u;
    auto uniform = [&] {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / float(1u << 24) * 2.0f - 1.0f;
    };
    double worst = 0.0;
    for (int k = 0; k < 20000; ++k) {
        const vec3 n = glm::normalize(vec3(uniform(), uniform(), uniform()) + vec3(1e-6f));
        const vec3 q = QuantizeNormal(n);
        // The angle from the chord, in double: acos of a float dot near 1 would measure float rounding.
        worst = std::max(worst, 2.0 * std::asin(glm::length(glm::dvec3(n) - glm::dvec3(q)) / 2.0));
        REQUIRE(std::abs(glm::length(q) - 1.0f) < 1e-6f);
    }
    INFO("largest angle " << worst << " rad");
    CHECK(worst < 1e-4);
    const std::vector<vec3> normals = {vec3(0, 0, 1), vec3(0.0f), vec3(0, 0, -1)};
    FrameInputs in;
    in.Allocate(3, 1);
    for (size_t i = 0; i < normals.size(); ++i) in.normal[i] = normals[i];
    std::vector<uint16_t> codes;
    ConvertForUpload(PlaneKind::Normal, in, codes);
    REQUIRE(codes.size() == 6);
    CHECK(int16_t(codes[0]) == 0);
    CHECK(int16_t(codes[1]) == 0);
    CHECK(int16_t(codes[2]) == -32768);
    CHECK(int16_t(codes[3]) == -32768);
    CHECK(int16_t(codes[4]) == 32767);
    CHECK(int16_t(codes[5]) == 32767);
}

// fp16 storage keeps depth and object id in one 32-bit code (shaders/common/depth_id.glsl): the
// depth truncated to 14 mantissa bits (relative error below 2^-14), the id modulo 511, the
// background's id and infinite depth kept; the object-id plane is then neither uploaded nor stored.
TEST_CASE("fp16 storage: depth and object id share one code, decoded as the shaders decode them") {
    CHECK(PlaneElementBytes(PlaneKind::Depth, Precision::Fp16) == 4);
    CHECK(ConvertedOnUpload(PlaneKind::Depth, Precision::Fp16));
    CHECK_FALSE(ConvertedOnUpload(PlaneKind::Depth, Precision::Fp32));
    CHECK(StoresObjectIdsInDepth(Precision::Fp16));
    CHECK_FALSE(StoresObjectIdsInDepth(Precision::Fp32));
    CHECK(ObjectIdOfCode(DepthIdCode(3.0f, kNoObject)) == kNoObject);
    CHECK(std::isinf(DepthOfCode(DepthIdCode(INFINITY, kNoObject))));  // the background's depth
    CHECK(DepthOfCode(DepthIdCode(1.0f, 7)) == 1.0f);                  // a power of two is exact
    CHECK(ObjectIdOfCode(DepthIdCode(1.0f, 0)) == 0u);
    CHECK(ObjectIdOfCode(DepthIdCode(1.0f, 510)) == 510u);
    CHECK(ObjectIdOfCode(DepthIdCode(1.0f, 511)) == 0u);               // ids wrap modulo 511
    CHECK(ObjectIdOfCode(DepthIdCode(1.0f, 1000)) == 489u);
    // A reset leaves depth 0 and the background's id, so that nothing reprojects onto it.
    CHECK(ObjectIdOfCode(ClearValue(PlaneKind::Depth, Precision::Fp16)) == kNoObject);
    CHECK(DepthOfCode(ClearValue(PlaneKind::Depth, Precision::Fp16)) == 0.0f);
    CHECK(ClearValue(PlaneKind::Depth, Precision::Fp32) == 0u);
    double worst = 0.0;
    for (float z = 1e-3f; z < 1e4f; z *= 1.001f) {
        const float q = DepthOfCode(DepthIdCode(z, 12345u));
        REQUIRE(q <= z);  // truncated, never rounded up
        worst = std::max(worst, double(z - q) / double(z));
    }
    INFO("largest relative depth error " << worst);
    CHECK(worst < 0x1p-14);
    CHECK(worst > 0x1p-15);  // the 9 id bits are really taken from the mantissa
    FrameInputs in;
    in.Allocate(2, 1);
    in.linearDepth[0] = 2.5f;
    in.objectId[0] = 42u;  // pixel 1 stays background (Allocate)
    std::vector<uint16_t> words;
    ConvertForUpload(PlaneKind::Depth, in, words);
    REQUIRE(words.size() == 4);
    for (size_t i = 0; i < 2; ++i)
        CHECK((uint32_t(words[2 * i]) | uint32_t(words[2 * i + 1]) << 16) == DepthIdCode(in.linearDepth[i], in.objectId[i]));
    CHECK(ObjectIdOfCode(uint32_t(words[0]) | uint32_t(words[1]) << 16) == 42u);
}
