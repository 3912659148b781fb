// SVGF on Vulkan vs the C++ reference, pass by pass, on random FrameInputs (64×64 and odd sizes, sub-pixel
// motion, random objects, HDR values): reprojection (illumination, moments, history length,
// colour history), filtered moments, each à-trous iteration, modulation; fp32 and fp16 histories;
// the weighted and combined variants; allocator accounting == memory plan; behaviour checks
// (disocclusion, camera cut, NaN); zero validation errors.
// Tolerance: |vk − ref| ≤ 2e-3·(1 + |ref|) (fp32; lavapipe's exp/pow differ from libm in the last
// bits and a few taps near a threshold may flip); fp16 histories 1e-2·(1 + |ref|).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <utility>

#include <glm/gtc/packing.hpp>

#include "denoise/denoiser_factory.h"
#include "denoise/memory_plan.h"
#include "denoise/reference/svgf_family_ref.h"
#include "denoise/vulkan/svgf_layout.h"
#include "denoise/vulkan/svgf_family_vk.h"
#include "denoise_svgf_scenes.h"
#include "test_support.h"
#include "vk/context.h"
#include "vk_test_support.h"

using namespace fovrt;
using fovrt::test::TestContext;
using namespace fovrt::test;

namespace {

struct ErrorStats {
    double maxAbs = 0.0;
    double maxRel = 0.0;  // |d| / (1 + |ref|)
    size_t bad = 0;
    void Add(float vk, float ref, double tol) {
        double d = std::abs(double(vk) - double(ref));
        if (!std::isfinite(vk) || !std::isfinite(ref)) d = INFINITY;  // a NaN reference must not pass
        maxAbs = std::max(maxAbs, d);
        double rel = d / (1.0 + std::abs(double(ref)));
        maxRel = std::max(maxRel, rel);
        if (rel > tol) ++bad;
    }
};

// Compares a GPU plane (floats, `components` per pixel) with a reference plane.
template <typename T>
ErrorStats Compare(const std::vector<float>& vk, const Plane<T>& ref, int components, double tol) {
    ErrorStats e;
    REQUIRE(vk.size() >= ref.size() * size_t(components));
    for (size_t i = 0; i < ref.size(); ++i)
        for (int c = 0; c < components; ++c) {
            const float* r = reinterpret_cast<const float*>(&ref[i]);
            e.Add(vk[i * size_t(components) + size_t(c)], r[c], tol);
        }
    return e;
}

std::vector<float> HalfsToFloats(const std::vector<uint8_t>& bytes) {
    std::vector<float> out(bytes.size() / 2);
    for (size_t i = 0; i < out.size(); ++i) {
        uint16_t h = uint16_t(bytes[2 * i] | (bytes[2 * i + 1] << 8));
        out[i] = glm::unpackHalf1x16(h);
    }
    return out;
}

using FrameMaker = FrameInputs (*)(int width, int height, uint32_t seed, uint32_t frame);

void RunPair(const DenoiserParams& params, const std::string& name, int frames, double tol,
             bool checkIllum, int width = 64, int height = 64, FrameMaker makeFrame = RandomFrame) {
    auto ctx = TestContext();
    SvgfFamilyVulkanDenoiser vk(FindDenoiserVariant(name), ctx, params);
    SvgfFamilyReferenceDenoiser ref(FindDenoiserVariant(name), params);
    Plane<vec3> outVk, outRef;
    const bool fp16 = params.precision == Precision::Fp16;
    auto read = [&](const std::string& buffer, bool atPrecision) {  // a history or an illumination plane
        auto bytes = vk.ReadBuffer(buffer);
        return atPrecision && fp16 ? HalfsToFloats(bytes) : AsFloats(bytes);
    };
    for (int t = 0; t < frames; ++t) {
        FrameInputs f = makeFrame(width, height, 1234, uint32_t(t));
        vk.Denoise(f, outVk);
        ref.Denoise(f, outRef);
        const std::string side = vk.LastWrittenSide();
        auto channels = SvgfChannels(params.svgf);
        for (size_t c = 0; c < channels.size(); ++c) {
            const std::string& ch = channels[c];
            const SvgfHistory& h = ref.CurrentHistory(c);
            INFO("frame " << t << " channel " << ch);
            auto eM = Compare(read(ch + ".moments." + side, true), h.moments, 2, tol);
            auto eL = Compare(read(ch + ".length." + side, true), h.length, 1, tol);
            auto eC = Compare(read(ch + ".color." + side, true), h.color, 3, tol);
            INFO("moments max rel " << eM.maxRel << ", length " << eL.maxRel << ", colour history "
                                     << eC.maxRel);
            CHECK(eM.bad == 0);
            CHECK(eL.bad == 0);
            CHECK(eC.bad == 0);
            if (params.svgf.weightBySampleCount) {
                auto eW = Compare(read(ch + ".weight." + side, true), h.weight, 1, tol);
                INFO("weight max rel " << eW.maxRel);
                CHECK(eW.bad == 0);
            }
            // The illumination planes still held after the frame (the other one's transient slot
            // may hold a plane written after it, e.g. the output).
            if (checkIllum) {
                int held = 0;
                for (int k = 0; k < 2; ++k) {
                    if (!vk.Readable(ch + ".illum" + std::to_string(k))) continue;
                    ++held;
                    auto eI = Compare(read(ch + ".illum" + std::to_string(k), true), ref.Illum(c, k), 4, tol);
                    INFO("illum" << k << " max rel " << eI.maxRel << " max abs " << eI.maxAbs);
                    CHECK(eI.bad == 0);
                }
                CHECK(held >= 1);  // the filtered illumination modulate read
            }
        }
        std::vector<float> o(outVk.size() * 3);
        std::memcpy(o.data(), outVk.data(), o.size() * 4);
        auto eO = Compare(o, outRef, 3, tol);
        if (t + 1 == frames)
            WARN(name << " " << width << "x" << height << " iterations " << params.svgf.atrousIterations << (fp16 ? " fp16" : "")
                      << (params.svgf.filterCombined ? " combined" : "") << ": output max rel error "
                      << eO.maxRel << ", max abs " << eO.maxAbs << " (validation "
                      << (ctx->validationEnabled() ? "on" : "off") << ")");
        INFO("frame " << t << " output max rel " << eO.maxRel << " max abs " << eO.maxAbs);
        CHECK(eO.bad == 0);
    }
    CHECK(vk.Stats().nonFiniteSamples == ref.Stats().nonFiniteSamples);
    CHECK(ctx->validationErrors() == 0);
}

}  // namespace

TEST_CASE("vulkan svgf passes match the C++ reference", "[vulkan][svgf]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    DenoiserParams p;
    SECTION("reproject + filter moments (no a-trous)") {
        p.svgf.atrousIterations = 0;
        RunPair(p, "svgf", 4, 2e-3, true);
    }
    SECTION("a-trous iteration 0 (feedback)") {
        p.svgf.atrousIterations = 1;
        RunPair(p, "svgf", 3, 2e-3, true);
    }
    SECTION("a-trous iterations 0-1") {
        p.svgf.atrousIterations = 2;
        RunPair(p, "svgf", 3, 2e-3, true);
    }
    SECTION("full svgf, 5 iterations, feedback of iteration 2 (Falcor)") {
        p.svgf.feedbackIteration = 2;
        RunPair(p, "svgf", 3, 2e-3, false);
    }
    // σn = 128 = 2^7 (default) evaluates w_n as 7 squarings; any other σn takes exp2(σn·log2).
    for (float sigmaNormal : {100.0f, 32.0f}) {
        SECTION("sigma_normal " + std::to_string(int(sigmaNormal)) + " (100: log2 path, 32: 5 squarings), 3 iterations") {
            p.svgf.sigmaNormal = sigmaNormal;
            p.svgf.atrousIterations = 3;
            RunPair(p, "svgf", 3, 2e-3, true);
        }
    }
    SECTION("svgf-weighted") {
        p.svgf.weightBySampleCount = true;
        p.svgf.atrousIterations = 2;
        RunPair(p, "svgf-weighted", 3, 2e-3, true);
    }
    SECTION("combined direct + indirect") {
        p.svgf.filterCombined = true;
        p.svgf.atrousIterations = 2;
        RunPair(p, "svgf", 3, 2e-3, true);
    }
    SECTION("fp16 histories") {
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        p.precision = Precision::Fp16;
        p.svgf.atrousIterations = 2;
        RunPair(p, "svgf", 3, 1e-2, false);
    }
    SECTION("fp16 histories, combined (one-channel a-trous)") {
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        p.precision = Precision::Fp16;
        p.svgf.filterCombined = true;
        p.svgf.atrousIterations = 2;
        RunPair(p, "svgf", 3, 1e-2, false);
    }
    SECTION("fp16 svgf-weighted, feedback of iteration 2") {
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        p.precision = Precision::Fp16;
        p.svgf.weightBySampleCount = true;
        p.svgf.atrousIterations = 3;
        p.svgf.feedbackIteration = 2;
        RunPair(p, "svgf-weighted", 3, 1e-2, false);
    }
    // Odd sizes: the à-trous filters 2×2 blocks at stride 2^i, so at the right and bottom edges a
    // block's partners fall outside the image (67 = 4·16 + 3, 45 = 2·16 + 13, 13 = 8 + 5, 7 < 8).
    SECTION("odd size 67x45, 5 iterations") {
        p.svgf.atrousIterations = 5;
        p.svgf.feedbackIteration = 2;
        RunPair(p, "svgf", 3, 2e-3, true, 67, 45);
    }
    SECTION("odd size 67x45, combined, 4 iterations") {
        p.svgf.filterCombined = true;
        p.svgf.atrousIterations = 4;
        RunPair(p, "svgf", 3, 2e-3, true, 67, 45);
    }
    SECTION("odd size 13x7, 4 iterations") {
        p.svgf.atrousIterations = 4;
        RunPair(p, "svgf", 3, 2e-3, true, 13, 7);
    }
    SECTION("fp16 histories, odd size 67x45, 3 iterations") {
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        p.precision = Precision::Fp16;
        p.svgf.atrousIterations = 3;
        RunPair(p, "svgf", 3, 1e-2, true, 67, 45);
    }
}

// The reprojection runs as two passes on Vulkan (bilinear taps on every pixel, then the 3×3
// fallback on the listed pixels only: shaders/common/reprojection.glsl); the reference does both in
// one loop. FallbackFrame sends every patch-edge column through the fallback.
// Pixels without a path sample (test::ZeroSampleFrame): svgf-weighted keeps their histories or,
// disoccluded, lets them hold nothing for the à-trous to fill; so does svgf where the spp map may
// hold zeros (sampleCountsMayBeZero: it reads the counts), and without that it takes them black.
TEST_CASE("vulkan svgf matches the reference with zero-sample pixels", "[vulkan][svgf]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    for (Precision precision : {Precision::Fp32, Precision::Fp16}) {
        if (precision == Precision::Fp16 && !TestContext()->supports16BitStorage()) continue;
        const double tol = precision == Precision::Fp16 ? 1e-2 : 2e-3;
        const std::string suffix = precision == Precision::Fp16 ? " fp16" : "";
        DenoiserParams p;
        p.precision = precision;
        p.svgf.atrousIterations = 3;
        SECTION("svgf-weighted, feedback of iteration 1" + suffix) {
            p.svgf.weightBySampleCount = true;
            RunPair(p, "svgf-weighted", 5, tol, true, 64, 64, ZeroSampleFrame);
        }
        SECTION("svgf-weighted, unfiltered colour history" + suffix) {
            p.svgf.weightBySampleCount = true;
            p.svgf.feedbackIteration = 0;
            RunPair(p, "svgf-weighted", 5, tol, true, 64, 64, ZeroSampleFrame);
        }
        SECTION("svgf" + suffix) {
            RunPair(p, "svgf", 5, tol, true, 64, 64, ZeroSampleFrame);
        }
        SECTION("svgf, sample counts may be zero, feedback of iteration 1" + suffix) {
            p.sampleCountsMayBeZero = true;
            RunPair(p, "svgf", 5, tol, true, 64, 64, ZeroSampleFrame);
        }
        SECTION("svgf, sample counts may be zero, unfiltered colour history" + suffix) {
            p.sampleCountsMayBeZero = true;
            p.svgf.feedbackIteration = 0;
            RunPair(p, "svgf", 5, tol, true, 64, 64, ZeroSampleFrame);
        }
        SECTION("svgf, sample counts may be zero, combined" + suffix) {
            p.sampleCountsMayBeZero = true;
            p.svgf.filterCombined = true;
            RunPair(p, "svgf", 5, tol, true, 64, 64, ZeroSampleFrame);
        }
    }
}

TEST_CASE("vulkan svgf: the 3x3 reprojection fallback pass matches the reference", "[vulkan][svgf]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    const int boxPixels = CountBoxFallbackPixels(FallbackFrame(64, 64, 1234, 1), FallbackFrame(64, 64, 1234, 0));
    INFO(boxPixels << " of 4096 pixels reproject through the 3x3 fallback");
    REQUIRE(boxPixels > 150);
    DenoiserParams p;
    p.svgf.atrousIterations = 1;
    SECTION("separate channels") { RunPair(p, "svgf", 4, 2e-3, true, 64, 64, FallbackFrame); }
    SECTION("combined") {
        p.svgf.filterCombined = true;
        RunPair(p, "svgf", 4, 2e-3, true, 64, 64, FallbackFrame);
    }
    SECTION("svgf-weighted, no a-trous (the colour history is written by the reprojection)") {
        p.svgf.weightBySampleCount = true;
        p.svgf.atrousIterations = 0;
        RunPair(p, "svgf-weighted", 4, 2e-3, true, 64, 64, FallbackFrame);
    }
    SECTION("fp16 histories") {
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        p.precision = Precision::Fp16;
        RunPair(p, "svgf", 4, 1e-2, false, 64, 64, FallbackFrame);
    }
}

TEST_CASE("sigma_normal = 2^k specialises w_n to k squarings, anything else to log2", "[svgf]") {
    CHECK(NormalWeightSquarings(128.0f) == 7);
    CHECK(NormalWeightSquarings(1.0f) == 0);
    CHECK(NormalWeightSquarings(4096.0f) == FOVRT_MAX_NORMAL_SQUARINGS);
    CHECK(NormalWeightSquarings(8192.0f) == -1);
    CHECK(NormalWeightSquarings(100.0f) == -1);
    CHECK(NormalWeightSquarings(0.0f) == -1);
    CHECK(NormalWeightSquarings(0.5f) == -1);
    CHECK(NormalWeightSquarings(128.5f) == -1);
}

TEST_CASE("vulkan allocator accounting equals the memory plan", "[vulkan][svgf]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto ctx = TestContext();
    // svgf also with the sample counts it uploads where the spp map may hold zeros.
    for (auto [name, zeroAware] : {std::pair{"svgf", false}, std::pair{"svgf-weighted", false}, std::pair{"svgf", true}})
        for (Precision prec : {Precision::Fp32, Precision::Fp16}) {
            INFO(name << (zeroAware ? " with sampleCountsMayBeZero" : ""));
            DenoiserParams p;
            p.precision = prec;
            p.sampleCountsMayBeZero = zeroAware;
            size_t before = ctx->allocator().LiveBytes();
            {
                auto d = CreateDenoiser(name, "vulkan", p, ctx.get());
                REQUIRE(d->Backend() == "vulkan");
                Plane<vec3> out;
                d->Denoise(RandomFrame(40, 24, 9, 0), out);
                auto plan = PlanDenoiserMemory(name, 40, 24, p);
                auto live = ctx->allocator().LiveAllocations();
                REQUIRE(live.size() == plan.size());
                std::sort(live.begin(), live.end(), [](auto& a, auto& b) { return a.name < b.name; });
                std::sort(plan.begin(), plan.end(), [](auto& a, auto& b) { return a.name < b.name; });
                for (size_t i = 0; i < plan.size(); ++i) {
                    CHECK(live[i].name == plan[i].name);
                    CHECK(live[i].bytes == plan[i].bytes);
                }
                CHECK(ctx->allocator().LiveBytes() - before == TotalBytes(plan));
            }
            CHECK(ctx->allocator().LiveBytes() == before);
        }
    CHECK(ctx->validationErrors() == 0);
}

TEST_CASE("vulkan svgf: disocclusion, camera cut, NaN never reaches history", "[vulkan][svgf]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto ctx = TestContext();
    StaticScene scene;
    scene.sigma = [](int, int) { return 0.3f; };
    DenoiserParams p;
    p.svgf.atrousIterations = 2;
    SvgfFamilyVulkanDenoiser d(FindDenoiserVariant("svgf"), ctx, p);
    Plane<vec3> out;
    auto length = [&](int x, int y) {
        return AsFloats(d.ReadBuffer("direct.length." + d.LastWrittenSide()))[size_t(y * 64 + x)];
    };
    for (uint32_t t = 0; t < 6; ++t) d.Denoise(scene.Frame(t), out);
    CHECK(length(10, 20) == Approx(6.0f));
    // Object id changes in a block → history 1 there, kept elsewhere; a NaN, an Inf, a negative.
    FrameInputs f = FaultyFrame(scene, 6);
    d.Denoise(f, out);
    CHECK(length(11, 11) == Approx(1.0f));
    CHECK(length(20, 40) == Approx(7.0f));
    CHECK(d.Stats().nonFiniteSamples == 2);
    CHECK(d.Stats().negativeSamples == 1);
    for (const char* buffer : {"direct.color.", "indirect.color.", "direct.moments.", "indirect.moments."}) {
        auto values = AsFloats(d.ReadBuffer(buffer + d.LastWrittenSide()));
        CHECK(std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); }));
    }
    for (size_t i = 0; i < out.size(); ++i) REQUIRE(IsFinite(out[i]));
    f = scene.Frame(7);
    f.cameraCut = true;
    d.Denoise(f, out);
    CHECK(length(20, 40) == Approx(1.0f));
    auto timings = d.LastTimings();
    if (ctx->supportsTimestamps()) {
        // upload, pack_guide, reproject, moments, 2 à-trous, modulate, download
        REQUIRE(timings.size() == 1 + 1 + 2 + 2 + 1 + 1);
        CHECK(timings[1].pass == "pack_guide");
        CHECK(timings[2].pass == "reproject");
    }
    // fp16 storage uploads the colour as halves: the NaN and the Inf still arrive as such and are
    // counted, the negative too, and nothing non-finite comes out.
    if (ctx->supports16BitStorage()) {
        p.precision = Precision::Fp16;
        SvgfFamilyVulkanDenoiser h(FindDenoiserVariant("svgf"), ctx, p);
        for (uint32_t t = 0; t < 6; ++t) h.Denoise(scene.Frame(t), out);
        h.Denoise(FaultyFrame(scene, 6), out);
        CHECK(h.Stats().nonFiniteSamples == 2);
        CHECK(h.Stats().negativeSamples == 1);
        for (size_t i = 0; i < out.size(); ++i) REQUIRE(IsFinite(out[i]));
    }
    CHECK(ctx->validationErrors() == 0);
}

TEST_CASE("factory: cpu backend, auto picks vulkan when present", "[vulkan][svgf]") {
    DenoiserParams p;
    CHECK(CreateDenoiser("svgf", "cpu", p)->Backend() == "cpu");
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    CHECK(CreateDenoiser("svgf-weighted", "auto", p, TestContext().get())->Backend() == "vulkan");
}

TEST_CASE("vulkan svgf: parameter change resets histories and rebuilds buffers", "[vulkan][svgf]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto ctx = TestContext();
    StaticScene scene;
    DenoiserParams p;
    p.svgf.atrousIterations = 1;
    SvgfFamilyVulkanDenoiser d(FindDenoiserVariant("svgf"), ctx, p);
    Plane<vec3> out;
    for (uint32_t t = 0; t < 3; ++t) d.Denoise(scene.Frame(t), out);
    CHECK(AsFloats(d.ReadBuffer("direct.length." + d.LastWrittenSide()))[20 * 64 + 10] == Approx(3.0f));
    p.svgf.filterCombined = true;
    d.SetParams(p);
    d.Denoise(scene.Frame(3), out);
    CHECK(AsFloats(d.ReadBuffer("combined.length." + d.LastWrittenSide()))[20 * 64 + 10] == Approx(1.0f));
    auto plan = PlanDenoiserMemory("svgf", 64, 64, p);
    CHECK(ctx->allocator().LiveBytes() == TotalBytes(plan));
    CHECK(ctx->validationErrors() == 0);
}
