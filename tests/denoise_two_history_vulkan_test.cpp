// two-history, asvgf, two-history-asvgf, the anti-lag variants, two-history-stable, its firefly and antilag variants and the clamp variants on Vulkan vs the C++
// reference, pass by pass, on random FrameInputs (64×64 and 67×45, sub-pixel motion, random objects, per-frame random
// sample counts, random gradient samples incl. duplicates per stratum): two_history_reproject (W_u, W_w, S_k, the
// luminance gradient g, moments), the colour histories fed back by à-trous iteration 1,
// two_history_gradient (q), asvgf_gradient_* ((δ̂, Δ̂)), asvgf_alpha (α or the anti-lag factor, λ),
// two_history_stabilize (the stabilised luminance), the firefly clamp in two_history_reproject, and the final output
// (blend, or the clamp variants' box, + remaining iterations + modulation); fp32 and fp16 histories; zero validation errors.
// Also: with constant n the Vulkan two-history equals the Vulkan SVGF.
// Tolerance: |vk − ref| ≤ 2e-3·(1 + |ref|) for every value, a non-finite value on either side
// counting as beyond it; fp16 histories 1e-2. A section that exercises a mechanism (the firefly
// clamp, the stabilisation clamp, the clamp box, the held choice, the anti-lag weight) first shows
// that the mechanism moves more than a tenth of the reference's output pixels by more than the
// fp32 tolerance, so that the comparison cannot pass with the mechanism missing on both sides.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <glm/gtc/packing.hpp>
#include <memory>
#include <random>

#include "denoise/reference/asvgf_ref.h"
#include "denoise/denoiser_factory.h"
#include "denoise/reference/svgf_family_ref.h"
#include "denoise/vulkan/svgf_family_vk.h"
#include "denoise_svgf_scenes.h"
#include "test_support.h"
#include "vk/context.h"
#include "vk_test_support.h"

using namespace fovrt;
using fovrt::test::RandomTwoHistoryFrame;
using fovrt::test::TestContext;

namespace {

std::vector<float> Floats(const std::vector<uint8_t>& bytes, bool half) {
    if (!half) return test::AsFloats(bytes);
    std::vector<float> out(bytes.size() / 2);
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = glm::unpackHalf1x16(uint16_t(bytes[2 * i] | (bytes[2 * i + 1] << 8)));
    return out;
}

constexpr double kTolerance = 2e-3;      // fp32 planes, and every plane not stored as a history
constexpr double kToleranceFp16 = 1e-2;  // fp16 histories, and the planes computed from them

// |a − b| / (1 + |b|), infinite when either is not finite (a NaN reference must not pass).
double RelativeError(float a, float b) {
    if (!std::isfinite(a) || !std::isfinite(b)) return INFINITY;
    return std::abs(double(a) - double(b)) / (1.0 + std::abs(double(b)));
}

struct Mismatch {
    double maxRel = 0.0;
    size_t bad = 0, total = 0;
};

template <typename T>
Mismatch Compare(const std::vector<float>& vk, const Plane<T>& ref, double tol) {
    constexpr size_t kComponents = sizeof(T) / sizeof(float);
    Mismatch m;
    REQUIRE(vk.size() >= ref.size() * kComponents);
    for (size_t i = 0; i < ref.size(); ++i) {
        const float* r = reinterpret_cast<const float*>(&ref[i]);
        for (size_t c = 0; c < kComponents; ++c) {
            const double rel = RelativeError(vk[i * kComponents + c], r[c]);
            m.maxRel = std::max(m.maxRel, rel);
            m.bad += rel > tol;
            ++m.total;
        }
    }
    return m;
}

// fp16 histories store W_w and S_k to ~5e-4: where V(p) is nearly flat (its curvature a − 2b + c
// below a tenth of a + c) that rounding moves p beyond the tolerance, and the device's and the
// reference's roundings differ by an ulp here and there. There I_w ≈ I_u (the sample counts of the
// history nearly equal), so the output, compared at every pixel, does not depend on p.
// `window` is where W_w and S_k are kept (p = 1 outside it, on both sides).
bool IllConditionedBlend(const TwoHistoryState& st, const HistoryWindow& window, size_t i) {
    const int j = window.Index(int(i % size_t(st.wu.width())), int(i / size_t(st.wu.width())));
    if (j < 0) return false;
    const double wu = st.wu[i], ww = st.ww[size_t(j)];
    if (!(wu > 0.0 && ww > 0.0)) return false;
    const vec3 s = st.powerSums[size_t(j)];
    const double a = s.z / (ww * ww), b = s.y / (ww * wu), c = s.x / (wu * wu);
    return std::abs(a - 2.0 * b + c) < 0.1 * (a + c);
}

// `gaze(frame)`, when given, is where the eye looks in each frame (the weighted history's window).
// `idStride` > 1 turns each object id k into k·idStride + 7 (with 511, every object shares one
// id code in fp16 storage: common/depth_id.glsl).
void RunPair(const DenoiserVariant& variant, const DenoiserParams& params, int frames, int width = 64,
             int height = 64, bool boxFallback = false, bool zeroSamples = false,
             const std::function<vec2(int)>& gaze = {}, uint32_t idStride = 1) {
    auto ctx = TestContext();
    SvgfFamilyVulkanDenoiser vk(variant, ctx, params);
    SvgfFamilyReferenceDenoiser ref(variant, params);
    const bool half = params.precision == Precision::Fp16;
    const double histTol = half ? kToleranceFp16 : kTolerance, tol = half ? kToleranceFp16 : kTolerance;
    const bool two = variant.twoHistory;
    const bool asvgf = variant.asvgfGradient;
    const std::vector<std::string> channels = params.svgf.filterCombined
                                                  ? std::vector<std::string>{"combined"}
                                                  : std::vector<std::string>{"direct", "indirect"};
    Plane<vec3> outVk, outRef;
    for (int frame = 0; frame < frames; ++frame) {
        FrameInputs f = RandomTwoHistoryFrame(width, height, uint32_t(frame), boxFallback);
        if (zeroSamples) f = test::WithZeroSamples(std::move(f), uint32_t(frame));
        if (gaze) f.gazePixel = gaze(frame);
        if (idStride > 1)
            for (size_t i = 0; i < f.objectId.size(); ++i)
                if (f.objectId[i] != kNoObject) f.objectId[i] = f.objectId[i] * idStride + 7u;
        vk.Denoise(f, outVk);
        ref.Denoise(f, outRef);
        const std::string side = vk.LastWrittenSide();
        const TwoHistoryState& st = ref.CurrentState();
        auto check = [&](const char* what, const Mismatch& m) {
            INFO(vk.Name() << (half ? " fp16" : " fp32") << " frame " << frame << " " << what
                           << ": max rel " << m.maxRel << ", " << m.bad << "/" << m.total
                           << " beyond tolerance");
            CHECK(m.bad == 0);
        };
        // p on both sides, a tie of the sample counts included (p = 1 on both: FOVRT_TWO_HISTORY_TIE);
        // with fp16 histories where p is determined (IllConditionedBlend), and not the held choice,
        // which carries the earlier frames' undetermined p.
        Plane<float> pVk, pRef;
        if (two && !(half && variant.hystereticChoice) && vk.ReadDebugView("p", pVk) && ref.ReadDebugView("p", pRef)) {
            size_t pBad = 0, pSkipped = 0;
            for (size_t i = 0; i < pRef.size(); ++i) {
                if (half && IllConditionedBlend(st, FrameWeightedWindow(variant, params, f), i)) {
                    ++pSkipped;
                    continue;
                }
                pBad += RelativeError(pVk[i], pRef[i]) > tol;
            }
            INFO(vk.Name() << (half ? " fp16" : " fp32") << " frame " << frame << ": p differs beyond tolerance at "
                           << pBad << " pixels (" << pSkipped << " ill-conditioned fp16 pixels not compared)");
            CHECK(pBad == 0);
        }
        check("output", Compare(test::AsFloats(vk.ReadBuffer("output")), outRef, tol));
        check("W_u", Compare(Floats(vk.ReadBuffer(channels[0] + ".length." + side), half), st.wu,
                             histTol));
        for (size_t c = 0; c < channels.size(); ++c) {
            check("moments", Compare(Floats(vk.ReadBuffer(channels[c] + ".moments." + side), half),
                                     st.moments[c], histTol));
            check("I_u history",
                  Compare(Floats(vk.ReadBuffer(channels[c] + ".color." + side), half), st.iu[c],
                          histTol));
            if (two)
                check("I_w history",
                      Compare(Floats(vk.ReadBuffer(channels[c] + ".wcolor." + side), half),
                              st.iw[c], histTol));
        }
        if (two) {
            check("W_w", Compare(Floats(vk.ReadBuffer("wweight." + side), half), st.ww, histTol));
            check("power sums",
                  Compare(Floats(vk.ReadBuffer("powerSums." + side), half), st.powerSums, histTol));
        }
        if (variant.emaGradient)  // one float per pixel: lum of g
            check("gradient",
                  Compare(Floats(vk.ReadBuffer("gradient." + side), half), st.gradient, histTol));
        if (variant.emaGradient)
            check("q", Compare(test::AsFloats(vk.ReadBuffer("q")), ref.Q(), tol));
        if (variant.stabilize)
            for (size_t c = 0; c < channels.size(); ++c)
                check("stabilised luminance",
                      Compare(Floats(vk.ReadBuffer(channels[c] + ".stableLum." + side), half),
                              ref.StableLuminance(c), histTol));
        if (asvgf) {
            check("alpha", Compare(test::AsFloats(vk.ReadBuffer("asvgf.alpha")), ref.Alpha(), tol));
            check("lambda",
                  Compare(test::AsFloats(vk.ReadBuffer("asvgf.lambda")), ref.Lambda(), tol));
            if (frame > 0) {
                const int gi = params.asvgf.gradientIterations;
                const char* last = gi > 0 && (gi - 1) % 2 == 0 ? "asvgf.grad1" : "asvgf.grad0";
                check("reconstructed gradient", Compare(test::AsFloats(vk.ReadBuffer(last)),
                                                        ref.ReconstructedGradient(), tol));
            }
        }
        if (frame == frames - 1) {
            std::string passes;
            for (const PassTiming& t : vk.LastTimings()) passes += t.pass + " ";
            INFO("passes: " << passes);
            CHECK(vk.LastTimings().size() >= 5);
        }
    }
    CHECK(vk.Stats().negativeSamples == ref.Stats().negativeSamples);
    CHECK(ctx->validationErrors() == 0);
}

// Output pixels (of the last of `frames` frames) where the C++ references of variant a with paramsA
// and variant b with paramsB differ by more than the fp32 tolerance in some channel: shows that a
// section comparing a's Vulkan passes exercised what sets a apart from b.
size_t ChangedPixels(const char* a, const DenoiserParams& paramsA, const char* b, const DenoiserParams& paramsB,
                     int frames, int width = 64, int height = 64) {
    SvgfFamilyReferenceDenoiser refA(FindDenoiserVariant(a), paramsA), refB(FindDenoiserVariant(b), paramsB);
    Plane<vec3> outA, outB;
    for (int frame = 0; frame < frames; ++frame) {
        const FrameInputs f = RandomTwoHistoryFrame(width, height, uint32_t(frame), false);
        refA.Denoise(f, outA);
        refB.Denoise(f, outB);
    }
    size_t changed = 0;
    for (size_t i = 0; i < outA.size(); ++i)
        changed += RelativeError(outA[i].x, outB[i].x) > kTolerance ||
                   RelativeError(outA[i].y, outB[i].y) > kTolerance ||
                   RelativeError(outA[i].z, outB[i].z) > kTolerance;
    return changed;
}

// Variant a with paramsA, which adds one mechanism to variant b with paramsB: the mechanism changes
// more than `minChanged` of the output pixels (a tenth unless a section says why less) beyond the
// tolerance, so the section exercises it; and a's Vulkan passes match a's reference.
void RunPairChanging(const char* a, const DenoiserParams& paramsA, const char* b, const DenoiserParams& paramsB,
                     int frames, int width = 64, int height = 64, double minChanged = 0.1) {
    const size_t changed = ChangedPixels(a, paramsA, b, paramsB, frames, width, height);
    INFO(a << " against " << b << ": " << changed << " of " << width * height
           << " output pixels differ beyond the tolerance");
    CHECK(double(changed) > minChanged * width * height);
    RunPair(FindDenoiserVariant(a), paramsA, frames, width, height);
}

void RunPairChanging(const char* a, const char* b, const DenoiserParams& params, int frames, int width = 64,
                     int height = 64) {
    RunPairChanging(a, params, b, params, frames, width, height);
}

}  // namespace

TEST_CASE("vulkan two-history / asvgf passes match the C++ reference",
          "[vulkan][two_history][asvgf]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    DenoiserParams params;
    for (const char* name : {"two-history", "asvgf", "two-history-asvgf", "asvgf-antilag", "two-history-asvgf-antilag"}) {
        const DenoiserVariant& v = FindDenoiserVariant(name);
        SECTION(std::string("fp32 separate channels: ") + std::string(v.name)) {
            RunPair(v, params, 4);
        }
    }
    // σn not a power of two: w_n through exp2(σn·log2) in the à-trous, moments, gradient and
    // A-SVGF reconstruction passes (2^k takes k squarings).
    for (const char* name : {"two-history", "two-history-asvgf"}) {
        const DenoiserVariant& v = FindDenoiserVariant(name);
        SECTION(std::string("fp32, sigma_normal 100 (log2 path): ") + std::string(v.name)) {
            params.svgf.sigmaNormal = 100.0f;
            params.svgf.atrousIterations = 2;
            RunPair(v, params, 3);
        }
    }
    SECTION("fp32 combined, feedback 0, 2 iterations: two-history") {
        params.svgf.filterCombined = true;
        params.svgf.feedbackIteration = 0;
        params.svgf.atrousIterations = 2;
        RunPair(FindDenoiserVariant("two-history"), params, 3);
    }
    SECTION("fp32 combined, feedback 1, 3 iterations: two-history (I_u + I_w as one a-trous pair)") {
        params.svgf.filterCombined = true;
        params.svgf.atrousIterations = 3;
        RunPair(FindDenoiserVariant("two-history"), params, 3);
    }
    // Odd size: 2×2 à-trous blocks whose partners fall outside the image at the borders.
    SECTION("fp32 separate channels, odd size 67x45, 4 iterations: two-history") {
        params.svgf.atrousIterations = 4;
        RunPair(FindDenoiserVariant("two-history"), params, 3, 67, 45);
    }
    SECTION("fp32 combined, odd size 67x45, 4 iterations: two-history") {
        params.svgf.filterCombined = true;
        params.svgf.atrousIterations = 4;
        RunPair(FindDenoiserVariant("two-history"), params, 3, 67, 45);
    }
    SECTION("fp32 combined: asvgf (one-channel a-trous)") {
        params.svgf.filterCombined = true;
        params.svgf.atrousIterations = 2;
        RunPair(FindDenoiserVariant("asvgf"), params, 3);
    }
    SECTION("fp16 combined: two-history") {
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        params.precision = Precision::Fp16;
        params.svgf.filterCombined = true;
        params.svgf.atrousIterations = 2;
        RunPair(FindDenoiserVariant("two-history"), params, 3);
    }
    SECTION("fp16: object ids beyond the depth code's 511 wrap on the device as in the reference") {
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        params.precision = Precision::Fp16;
        params.svgf.atrousIterations = 2;
        for (const char* name : {"two-history-asvgf-stable-hysteresis", "asvgf"})
            RunPair(FindDenoiserVariant(name), params, 3, 64, 64, false, false, {}, 511u);
    }
    SECTION("fp32, no a-trous: two-history-asvgf") {
        params.svgf.atrousIterations = 0;
        RunPair(FindDenoiserVariant("two-history-asvgf"), params, 3);
    }
    // Every patch-edge column through the 3×3 fallback (the Vulkan reprojection's box pass):
    // a broken box pass changes ~6 % of the pixels, beyond the 0.5 % tolerated above.
    for (const char* name : {"two-history", "asvgf", "two-history-asvgf", "asvgf-antilag"}) {
        const DenoiserVariant& v = FindDenoiserVariant(name);
        SECTION(std::string("fp32, 3x3 reprojection fallback: ") + std::string(v.name)) {
            const int boxPixels = test::CountBoxFallbackPixels(RandomTwoHistoryFrame(64, 64, 1, true),
                                                               RandomTwoHistoryFrame(64, 64, 0, true));
            INFO(boxPixels << " of 4096 pixels reproject through the 3x3 fallback");
            REQUIRE(boxPixels > 150);
            params.svgf.atrousIterations = 1;
            RunPair(v, params, 4, 64, 64, true);
        }
    }
    SECTION("fp32 combined, 3x3 reprojection fallback: two-history") {
        params.svgf.filterCombined = true;
        params.svgf.atrousIterations = 1;
        RunPair(FindDenoiserVariant("two-history"), params, 4, 64, 64, true);
    }
    // The stabilisation pass (its own bilinear reprojection, 3×3 moments, clamp) on every layout.
    SECTION("two-history-stable: fp32 separate channels, thesis iterations") {
        params.svgf.atrousIterations = 2;
        RunPair(FindDenoiserVariant("two-history-stable"), params, 4);
    }
    SECTION("two-history-stable: fp32 combined, odd size 67x45, 3 iterations") {
        params.svgf.filterCombined = true;
        params.svgf.atrousIterations = 3;
        RunPair(FindDenoiserVariant("two-history-stable"), params, 3, 67, 45);
    }
    // The stabilisation's clamp (k = 0.5) against the same variant with the clamp off (k = 1e6).
    SECTION("two-history-stable: the history clamp, against k = 1e6") {
        params.svgf.atrousIterations = 2;
        params.twoHistoryStable.sigmaScale = 0.5f;
        DenoiserParams unclamped = params;
        unclamped.twoHistoryStable.sigmaScale = 1e6f;
        RunPairChanging("two-history-stable", params, "two-history-stable", unclamped, 6);
    }
    SECTION("two-history-stable: 3x3 reprojection fallback pixels restart the stabilisation") {
        params.svgf.atrousIterations = 1;
        params.twoHistoryStable.sigmaScale = 0.5f;  // the clamp engaged on many pixels
        RunPair(FindDenoiserVariant("two-history-stable"), params, 4, 64, 64, true);
    }
    SECTION("two-history-stable: fp16 histories") {
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        params.precision = Precision::Fp16;
        RunPair(FindDenoiserVariant("two-history-stable"), params, 3);
    }
    // The firefly clamp (k = 0.5 so that it engages on many pixels once W_u,prev ≥ 4: frames 5, 6).
    SECTION("two-history-stable-firefly: fp32 separate channels") {
        params.svgf.atrousIterations = 2;
        params.twoHistory.fireflySigma = 0.5f;
        RunPairChanging("two-history-stable-firefly", "two-history-stable", params, 6);
    }
    SECTION("two-history-stable-firefly: fp32 combined, odd size 67x45") {
        params.svgf.filterCombined = true;
        params.svgf.atrousIterations = 3;
        params.twoHistory.fireflySigma = 0.5f;
        RunPairChanging("two-history-stable-firefly", "two-history-stable", params, 6, 67, 45);
    }
    SECTION("two-history-stable-firefly: 3x3 reprojection fallback pixels") {
        params.svgf.atrousIterations = 1;
        params.twoHistory.fireflySigma = 0.5f;
        RunPair(FindDenoiserVariant("two-history-stable-firefly"), params, 6, 64, 64, true);
    }
    SECTION("two-history-stable-firefly: fp16 histories") {
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        params.precision = Precision::Fp16;
        params.twoHistory.fireflySigma = 0.5f;
        RunPair(FindDenoiserVariant("two-history-stable-firefly"), params, 6);
    }
    // The stabilisation weight driven by q (q0 = 0: every pixel's weight follows its q; α_s = 0.02 and
    // 8 frames, so that q rather than α_s or the warm-up sets the weight on many pixels). No à-trous
    // after the blend: with 2 iterations the weight moves only ~7 % of the pixels beyond the tolerance.
    SECTION("two-history-stable-antilag: fp32 separate channels") {
        params.svgf.atrousIterations = 0;
        params.twoHistoryStable.antilagQ = 0.0f;
        params.twoHistoryStable.alpha = 0.02f;
        RunPairChanging("two-history-stable-antilag", "two-history-stable", params, 8);
    }
    SECTION("two-history-stable-antilag: fp32 combined, odd size 67x45, fp16 histories") {
        params.svgf.filterCombined = true;
        params.svgf.atrousIterations = 0;
        params.twoHistoryStable.antilagQ = 0.0f;
        params.twoHistoryStable.alpha = 0.02f;
        RunPairChanging("two-history-stable-antilag", "two-history-stable", params, 8, 67, 45);
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        params.precision = Precision::Fp16;
        RunPair(FindDenoiserVariant("two-history-stable-antilag"), params, 3);
    }
    // The same weight driven by A-SVGF's λ (the anti-lag family's q), against the variant without it.
    SECTION("two-history-asvgf-stable-antilag: fp32 separate channels and fp16") {
        params.svgf.atrousIterations = 2;
        params.twoHistoryStable.antilagQ = 0.0f;
        params.twoHistoryStable.alpha = 0.02f;
        RunPair(FindDenoiserVariant("two-history-asvgf-stable-antilag"), params, 6);
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        params.precision = Precision::Fp16;
        RunPair(FindDenoiserVariant("two-history-asvgf-stable-antilag"), params, 3);
    }
    // The clamp variants' box in two_history_blend (k = 0.5: I_u clamped on many pixels).
    SECTION("two-history-clamp: fp32 separate channels") {
        params.svgf.atrousIterations = 2;
        params.twoHistory.clampSigma = 0.5f;
        RunPairChanging("two-history-clamp", "two-history", params, 4);
    }
    SECTION("two-history-clamp: fp32 combined, odd size 67x45, blend without a-trous") {
        params.svgf.filterCombined = true;
        params.svgf.atrousIterations = 0;
        params.twoHistory.clampSigma = 0.5f;
        RunPairChanging("two-history-clamp", "two-history", params, 4, 67, 45);
    }
    SECTION("two-history-stable-clamp: fp32 combined, odd size 67x45, 3 iterations") {
        params.svgf.filterCombined = true;
        params.svgf.atrousIterations = 3;
        params.twoHistory.clampSigma = 0.5f;
        RunPair(FindDenoiserVariant("two-history-stable-clamp"), params, 4, 67, 45);
    }
    SECTION("two-history-clamp and two-history-stable-clamp: fp16 histories") {
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        params.precision = Precision::Fp16;
        params.twoHistory.clampSigma = 0.5f;
        RunPair(FindDenoiserVariant("two-history-clamp"), params, 3);
        RunPair(FindDenoiserVariant("two-history-stable-clamp"), params, 3);
    }
    // The hysteresis variants' held choice (two_history_choice, then the blend reading it): band
    // 0.05 and rate 0.25, so the held choice differs from p on many pixels.
    SECTION("two-history-hysteresis: fp32 separate channels") {
        params.svgf.atrousIterations = 2;
        params.twoHistory.choiceBand = 0.05f;
        RunPairChanging("two-history-hysteresis", "two-history", params, 6);
    }
    SECTION("two-history-hysteresis: fp32 combined, odd size 67x45, blend without a-trous") {
        params.svgf.filterCombined = true;
        params.svgf.atrousIterations = 0;
        params.twoHistory.choiceBand = 0.05f;
        RunPairChanging("two-history-hysteresis", "two-history", params, 6, 67, 45);
    }
    SECTION("two-history-hysteresis: 3x3 reprojection fallback pixels") {
        params.svgf.atrousIterations = 1;
        params.twoHistory.choiceBand = 0.05f;
        RunPair(FindDenoiserVariant("two-history-hysteresis"), params, 6, 64, 64, true);
    }
    SECTION("two-history-stable-hysteresis: fp32 combined, 3 iterations; both hysteresis variants fp16") {
        params.svgf.filterCombined = true;
        params.svgf.atrousIterations = 3;
        params.twoHistory.choiceBand = 0.05f;
        RunPair(FindDenoiserVariant("two-history-stable-hysteresis"), params, 6, 67, 45);
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        params.precision = Precision::Fp16;
        RunPair(FindDenoiserVariant("two-history-hysteresis"), params, 4);
        RunPair(FindDenoiserVariant("two-history-stable-hysteresis"), params, 4);
    }
    // Here λ, not p, sets most of the blend, and the stabilisation smooths what p changes: the held
    // choice (rate 0.05, 10 frames) moves ~10 % of the pixels beyond the tolerance, so a twentieth.
    SECTION("two-history-asvgf-stable-hysteresis: fp32 separate channels") {
        params.svgf.atrousIterations = 2;
        params.twoHistory.choiceBand = 0.05f;
        params.twoHistory.choiceRate = 0.05f;
        RunPairChanging("two-history-asvgf-stable-hysteresis", params, "two-history-asvgf-stable-antilag", params, 10,
                        64, 64, 0.05);
    }
    SECTION("fp16 histories: two-history, asvgf and asvgf-antilag") {
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        params.precision = Precision::Fp16;
        RunPair(FindDenoiserVariant("two-history"), params, 3);
        RunPair(FindDenoiserVariant("asvgf"), params, 3);
        RunPair(FindDenoiserVariant("asvgf-antilag"), params, 3);
    }
}

// Pixels without a path sample (sample count 0; test::WithZeroSamples): kept histories, pixels that
// hold nothing and are filled by the à-trous, on both backends alike. asvgf and asvgf-antilag
// read the counts where the spp map may hold zeros (sampleCountsMayBeZero), and take such a pixel
// as black without it; both runs are compared.
TEST_CASE("vulkan two-history family matches the reference with zero-sample pixels", "[vulkan][two_history]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    for (Precision precision : {Precision::Fp32, Precision::Fp16}) {
        if (precision == Precision::Fp16 && !TestContext()->supports16BitStorage()) continue;
        for (const DenoiserVariant& variant : DenoiserVariants()) {
            if (variant.family != DenoiserFamily::TwoHistory) continue;
            for (bool zeroAware : {false, true}) {
                if (zeroAware && variant.needsSampleCount) continue;  // it reads the counts anyway
                DenoiserParams params = ParamsForDenoiser(std::string(variant.name), DenoiserParams{});
                params.precision = precision;
                params.sampleCountsMayBeZero = zeroAware;
                INFO(variant.name << (precision == Precision::Fp16 ? " fp16" : " fp32")
                                  << (zeroAware ? ", sample counts may be zero" : ""));
                RunPair(variant, params, 5, 64, 64, false, true);
            }
        }
    }
}

// The weighted history kept in a window that follows the gaze (denoise.two_history.window): the
// window (32×32 of 64×64) jumps with the gaze every frame, so pixels leave it (the unweighted
// history alone), enter it (a weighted history restarted from I_u) and stay (gathered from the
// previous window's planes); W_w, S_k and I_w are compared in window-sized planes, p over the image.
TEST_CASE("the weighted history in a gaze-following window matches the reference on Vulkan", "[vulkan][two_history]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    const auto gaze = [](int frame) { return vec2(8.0f + 11.0f * float(frame), 44.0f - 6.0f * float(frame)); };
    DenoiserParams whole;
    DenoiserParams windowed;
    windowed.twoHistory.window = 0.5f;
    {
        const size_t changed = ChangedPixels("two-history", windowed, "two-history", whole, 5);
        INFO(changed << " of 4096 output pixels differ from the whole-image window beyond the tolerance");
        CHECK(changed > 400);
    }
    SECTION("two-history, fp32 separate channels") { RunPair(FindDenoiserVariant("two-history"), windowed, 6, 64, 64, false, false, gaze); }
    SECTION("two-history, fp32 combined, odd size 67x45, feedback 0") {
        DenoiserParams p = windowed;
        p.svgf.filterCombined = true;
        p.svgf.feedbackIteration = 0;
        RunPair(FindDenoiserVariant("two-history"), p, 6, 67, 45, false, false, gaze);
    }
    SECTION("hysteresis, clamp, stable-antilag and zero-sample pixels") {
        for (const char* name : {"two-history-hysteresis", "two-history-clamp", "two-history-asvgf-stable-antilag"}) {
            INFO(name);
            RunPair(FindDenoiserVariant(name), ParamsForDenoiser(name, windowed), 5, 64, 64, false, false, gaze);
        }
        RunPair(FindDenoiserVariant("two-history"), windowed, 5, 64, 64, false, true, gaze);
    }
    SECTION("fp16 histories") {
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        DenoiserParams p = windowed;
        p.precision = Precision::Fp16;
        RunPair(FindDenoiserVariant("two-history"), p, 5, 64, 64, false, false, gaze);
    }
}

// Outside the weighted history's window two-history takes the unweighted history, which is SVGF's
// whatever the sample counts: with one à-trous iteration (none after the blend to carry the
// window's pixels out) its output there equals svgf's, on the reference and on Vulkan, and inside
// it does not.
TEST_CASE("outside the weighted history's window two-history is svgf", "[vulkan][two_history]") {
    DenoiserParams params;
    params.svgf.atrousIterations = 1;
    params.twoHistory.window = 0.4f;
    const vec2 gaze(10.0f, 12.0f);  // the window in the top-left corner
    const HistoryWindow window = WeightedWindowAt(64, 64, 0.4f, gaze);
    REQUIRE(window.origin == ivec2(0));
    REQUIRE(window.size == ivec2(26));
    auto compare = [&](Denoiser& twoHistory, Denoiser& svgf) {
        Plane<vec3> a, b;
        double outside = 0.0;
        size_t insideChanged = 0;
        for (uint32_t frame = 0; frame < 6; ++frame) {
            FrameInputs f = RandomTwoHistoryFrame(64, 64, frame);
            f.gazePixel = gaze;
            twoHistory.Denoise(f, a);
            svgf.Denoise(f, b);
            for (int y = 0; y < 64; ++y)
                for (int x = 0; x < 64; ++x)
                    for (int c = 0; c < 3; ++c) {
                        const double rel = RelativeError(a(x, y)[c], b(x, y)[c]);
                        if (window.Index(x, y) < 0) outside = std::max(outside, rel);
                        else if (frame == 5 && c == 0) insideChanged += rel > kTolerance;
                    }
        }
        INFO(twoHistory.Backend() << ": outside the window max relative difference " << outside << "; inside "
                                  << insideChanged << " of " << window.Pixels() << " pixels differ");
        CHECK(outside < 1e-4);
        CHECK(insideChanged > window.Pixels() / 10);
        // The views over the image: W_w is 0 and p is 1 outside the window; inside, W_w counts samples.
        Plane<float> samples, p;
        REQUIRE(twoHistory.ReadDebugView("historySamples", samples));
        REQUIRE(twoHistory.ReadDebugView("p", p));
        size_t outsideWrong = 0, insideHeld = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                if (window.Index(x, y) < 0) outsideWrong += samples(x, y) != 0.0f || p(x, y) != 1.0f;
                else insideHeld += samples(x, y) > 0.0f;
            }
        CHECK(outsideWrong == 0);
        CHECK(insideHeld > window.Pixels() / 2);
    };
    {
        SvgfFamilyReferenceDenoiser th(FindDenoiserVariant("two-history"), params), svgf(FindDenoiserVariant("svgf"), params);
        compare(th, svgf);
    }
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto ctx = TestContext();
    SvgfFamilyVulkanDenoiser th(FindDenoiserVariant("two-history"), ctx, params), svgf(FindDenoiserVariant("svgf"), ctx, params);
    compare(th, svgf);
    CHECK(ctx->validationErrors() == 0);
}

TEST_CASE("vulkan two-history with constant n equals vulkan svgf", "[vulkan][two_history]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto ctx = TestContext();
    DenoiserParams params;
    SvgfFamilyVulkanDenoiser th(FindDenoiserVariant("two-history"), ctx, params);
    SvgfFamilyVulkanDenoiser svgf(FindDenoiserVariant("svgf"), ctx, params);
    Plane<vec3> a, b;
    double maxRel = 0.0;
    for (uint32_t frame = 0; frame < 6; ++frame) {
        FrameInputs f = test::RandomFrame(64, 64, 9, frame);
        for (size_t i = 0; i < f.sampleCount.size(); ++i) f.sampleCount[i] = 4;
        th.Denoise(f, a);
        svgf.Denoise(f, b);
        for (size_t i = 0; i < a.size(); ++i)
            for (int c = 0; c < 3; ++c)
                maxRel = std::max(maxRel,
                                  double(std::abs(a[i][c] - b[i][c])) / (1.0 + std::abs(b[i][c])));
    }
    INFO("max relative difference " << maxRel);
    CHECK(maxRel < 1e-4);
    CHECK(ctx->validationErrors() == 0);
}

TEST_CASE("factory creates the two-history family on both backends", "[vulkan][two_history]") {
    DenoiserParams params;
    for (const char* name : {"two-history", "asvgf", "two-history-asvgf"}) {
        auto cpu = CreateDenoiser(name, "cpu", params);
        CHECK(cpu->Name() == name);
        CHECK(cpu->Backend() == "cpu");
        CHECK(!PlanDenoiserMemory(name, 64, 64, params).empty());
    }
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    for (const char* name : {"two-history", "asvgf", "two-history-asvgf"}) {
        auto vk = CreateDenoiser(name, "vulkan", params, TestContext().get());
        CHECK(vk->Name() == name);
        CHECK(vk->Backend() == "vulkan");
    }
}

// The staging ring (DenoiserParams::transferRingBytes, vk/transfer_ring.h): a frame whose
// uploads and downloads go through a ring far smaller than they are, in hundreds of submits, gives
// the bytes that one submit gives, frame after frame (histories carried), for a variant that
// uploads every kind of plane (sample counts, A-SVGF's gradient samples).
TEST_CASE("a frame streamed through a small staging ring equals the frame submitted at once", "[vulkan][two_history]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto ctx = TestContext();
    for (const char* name : {"svgf", "two-history-asvgf-stable-antilag"}) {
        INFO(name);
        const DenoiserVariant& variant = FindDenoiserVariant(name);
        DenoiserParams whole = ParamsForDenoiser(name, DenoiserParams{});
        DenoiserParams streamed = whole;
        streamed.transferRingBytes = 1000;  // not a multiple of the 16-byte alignment
        REQUIRE(BuildDenoiserPlan(name, streamed, 64, 64).buffers.size() ==
                BuildDenoiserPlan(name, whole, 64, 64).buffers.size());
        SvgfFamilyVulkanDenoiser a(variant, ctx, whole), b(variant, ctx, streamed);
        Plane<vec3> outA, outB;
        for (uint32_t frame = 0; frame < 4; ++frame) {
            const FrameInputs f = RandomTwoHistoryFrame(64, 64, frame);
            a.Denoise(f, outA);
            b.Denoise(f, outB);
            REQUIRE(outA.size() == outB.size());
            CHECK(std::memcmp(outA.data(), outB.data(), outA.bytes()) == 0);
        }
        const std::string length = "direct.length." + a.LastWrittenSide();
        CHECK(a.ReadBuffer(length) == b.ReadBuffer(length));
        CHECK(a.Stats().nonFiniteSamples == b.Stats().nonFiniteSamples);
    }
    CHECK(ctx->validationErrors() == 0);
}

// Every composition of the gradient / two-history pass family (denoise/variants.h: 54 with the
// two-history family, and svgf+asvgf with and without anti-lag), on Vulkan against the C++
// reference: both follow the row's flags, so a combination that no alias names runs on both alike.
// Each in fp32 and in fp16 storage (16-bit histories, illumination and inputs, octahedral normals).
TEST_CASE("every composition of the two-history pass family matches the reference on Vulkan", "[vulkan][two_history]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    size_t run = 0;
    const bool half = TestContext()->supports16BitStorage();
    for (const std::string& name : DenoiserCompositions()) {
        const DenoiserVariant& variant = FindDenoiserVariant(name);
        if (variant.family != DenoiserFamily::TwoHistory) continue;
        INFO(name);
        DenoiserParams params = ParamsForDenoiser(name, DenoiserParams{});
        RunPair(variant, params, 3);
        if (half) {
            params.precision = Precision::Fp16;
            RunPair(variant, params, 3);
        }
        ++run;
    }
    CHECK(run == 2 + 3 * 2 * 3 * 3);
    CHECK(TestContext()->validationErrors() == 0);
    if (!half) FOVRT_SKIP("no 16-bit storage: the compositions ran in fp32 only");
}
