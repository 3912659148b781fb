// Pixels with zero path samples (a periphery below 1 spp) in the SVGF-family denoisers, on the C++
// reference (the Vulkan passes are held to it by denoise_svgf_vulkan_test and
// denoise_two_history_vulkan_test on the same inputs). The variants that weigh by the sample
// count always read it; svgf, asvgf and asvgf-antilag read it with
// DenoiserParams::sampleCountsMayBeZero (a run sets it when its foveation goes below 1 spp):
// - a pixel without a sample keeps its reprojected history as it is: no colour enters, the history
//   length (SVGF's length, two-history's W_u) and the weights do not advance;
// - without the switch svgf, asvgf and asvgf-antilag take the pixel's 0 as a black sample;
// - a disoccluded pixel without a sample holds nothing and its neighbours fill it;
// - no NaN or Inf in any history, whatever the mask;
// - the memory plan of every variant is what it was before zero-sample pixels were accepted, and
//   the switch adds the sample-count plane (and its staging) to the three that lacked it only.
#include <cmath>
#include <iterator>
#include <string>
#include <vector>

#include "denoise/denoiser_factory.h"
#include "denoise/memory_plan.h"
#include "denoise/pass_plan.h"
#include "denoise/planes.h"
#include "denoise/reference/svgf_family_ref.h"
#include "denoise/variants.h"
#include "denoise_svgf_scenes.h"
#include "test_support.h"

using namespace fovrt;

namespace {

constexpr int kW = 48, kH = 32;

// A still frame (every pixel reprojects onto itself with one tap) with `n` samples everywhere.
FrameInputs StillFrame(uint32_t frame, uint16_t n) {
    FrameInputs f = test::RandomFrame(kW, kH, 11, frame);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            f.prevPixel(x, y) = vec2(float(x) + 0.5f, float(y) + 0.5f);
            f.sampleCount(x, y) = n;
        }
    f.gradientSamples.clear();
    return f;
}

bool NoSample(int x, int y) { return (x + y) % 3 == 0; }

// Frame 2 of a still view: NoSample's pixels without a path sample (count 0, colour 0), the
// others with 2.
FrameInputs MaskedStillFrame() {
    FrameInputs f = StillFrame(2, 2);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            if (NoSample(x, y)) {
                f.sampleCount(x, y) = 0;
                f.direct(x, y) = f.indirect(x, y) = vec3(0.0f);
            }
    return f;
}

// The parameters `variant` runs with where the spp map may hold zeros (what a run with a
// foveation below 1 spp gives it), the colour history written by the reprojection itself.
DenoiserParams ZeroAwareParams(const DenoiserVariant& variant, bool sampleCountsMayBeZero = true) {
    DenoiserParams params = ParamsForDenoiser(std::string(variant.name), DenoiserParams{});
    params.sampleCountsMayBeZero = sampleCountsMayBeZero;
    params.svgf.feedbackIteration = 0;
    return params;
}

// One channel's history at pixel i as the reprojection leaves it: SVGF's length and colour
// history, or the two-history family's W_u and I_u.
struct PixelHistory {
    float length;
    vec3 color;
};
PixelHistory HistoryAt(const SvgfFamilyReferenceDenoiser& ref, bool twoHistoryFamily, size_t i) {
    if (twoHistoryFamily) return {ref.CurrentState().wu[i], ref.CurrentState().iu[0][i]};
    return {ref.CurrentHistory(0).length[i], ref.CurrentHistory(0).color[i]};
}

// The variants that weigh by no sample count of their own (svgf, asvgf, asvgf-antilag).
bool ReadsCountsOnlyForZeros(const DenoiserVariant& variant) {
    return variant.family != DenoiserFamily::Rae && !variant.needsSampleCount;
}

template <typename T>
bool AllFinite(const Plane<T>& plane) {
    const float* v = reinterpret_cast<const float*>(plane.data());
    for (size_t i = 0; i < plane.size() * sizeof(T) / sizeof(float); ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}

// Every history plane the reference keeps for `ref`'s variant is finite.
void CheckHistoriesFinite(const SvgfFamilyReferenceDenoiser& ref, bool twoHistoryFamily) {
    if (!twoHistoryFamily) {
        for (size_t c = 0; c < ref.ChannelCount(); ++c) {
            const SvgfHistory& h = ref.CurrentHistory(c);
            CHECK(AllFinite(h.color));
            CHECK(AllFinite(h.moments));
            CHECK(AllFinite(h.length));
            CHECK(AllFinite(h.weight));
        }
        return;
    }
    const TwoHistoryState& st = ref.CurrentState();
    CHECK(AllFinite(st.wu));
    CHECK(AllFinite(st.ww));
    CHECK(AllFinite(st.powerSums));
    CHECK(AllFinite(st.gradient));
    for (size_t c = 0; c < ref.ChannelCount(); ++c) {
        CHECK(AllFinite(st.iu[c]));
        CHECK(AllFinite(st.iw[c]));
        CHECK(AllFinite(st.moments[c]));
    }
}

}  // namespace

TEST_CASE("a pixel without a path sample keeps its history: no colour enters, the length stays",
          "[zero_samples]") {
    for (const DenoiserVariant& variant : DenoiserVariants()) {
        if (variant.family == DenoiserFamily::Rae) continue;
        const std::string name(variant.name);
        INFO(name);
        SvgfFamilyReferenceDenoiser ref(variant, ZeroAwareParams(variant));
        const bool two = variant.family == DenoiserFamily::TwoHistory;
        const bool weighted = variant.twoHistory;  // I_w, W_w and S_k kept
        Plane<vec3> out;
        ref.Denoise(StillFrame(0, 2), out);
        ref.Denoise(StillFrame(1, 2), out);
        // Frame 1's histories, copied: frame 2 reads them as its previous ones.
        const TwoHistoryState before = two ? ref.CurrentState() : TwoHistoryState{};
        const SvgfHistory beforeSvgf = two ? SvgfHistory{} : ref.CurrentHistory(0);
        const FrameInputs f = MaskedStillFrame();
        ref.Denoise(f, out);
        CheckHistoriesFinite(ref, two);
        size_t kept = 0, advanced = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                if (f.objectId(x, y) == kNoObject) continue;
                if (two) {
                    const TwoHistoryState& st = ref.CurrentState();
                    if (NoSample(x, y)) {
                        REQUIRE(st.wu(x, y) == before.wu(x, y));
                        REQUIRE(st.iu[0](x, y) == before.iu[0](x, y));
                        REQUIRE(st.moments[0](x, y) == before.moments[0](x, y));
                        if (weighted) {
                            REQUIRE(st.ww(x, y) == before.ww(x, y));
                            REQUIRE(st.powerSums(x, y) == before.powerSums(x, y));
                            REQUIRE(st.iw[0](x, y) == before.iw[0](x, y));
                        }
                        ++kept;
                    } else {
                        advanced += st.wu(x, y) > before.wu(x, y);
                    }
                } else {
                    const SvgfHistory& h = ref.CurrentHistory(0);
                    if (NoSample(x, y)) {
                        REQUIRE(h.length(x, y) == beforeSvgf.length(x, y));
                        if (variant.weightBySampleCount) REQUIRE(h.weight(x, y) == beforeSvgf.weight(x, y));
                        REQUIRE(h.color(x, y) == beforeSvgf.color(x, y));
                        REQUIRE(h.moments(x, y) == beforeSvgf.moments(x, y));
                        ++kept;
                    } else {
                        advanced += h.length(x, y) > beforeSvgf.length(x, y);
                    }
                }
            }
        CHECK(kept > size_t(kW * kH / 4));
        CHECK(advanced > size_t(kW * kH / 2));
    }
}

// The switch is what keeps the history: without it the pixel's 0 enters as a black sample.
TEST_CASE("without sampleCountsMayBeZero svgf, asvgf and asvgf-antilag take a zero-sample pixel as black",
          "[zero_samples]") {
    size_t variants = 0;
    for (const DenoiserVariant& variant : DenoiserVariants()) {
        if (!ReadsCountsOnlyForZeros(variant)) continue;
        ++variants;
        for (bool zeroAware : {true, false}) {
            INFO(variant.name << (zeroAware ? " with" : " without") << " sampleCountsMayBeZero");
            SvgfFamilyReferenceDenoiser ref(variant, ZeroAwareParams(variant, zeroAware));
            const bool two = variant.family == DenoiserFamily::TwoHistory;
            Plane<vec3> out;
            ref.Denoise(StillFrame(0, 2), out);
            ref.Denoise(StillFrame(1, 2), out);
            std::vector<PixelHistory> before;
            for (size_t i = 0; i < size_t(kW * kH); ++i) before.push_back(HistoryAt(ref, two, i));
            const FrameInputs f = MaskedStillFrame();
            ref.Denoise(f, out);
            size_t kept = 0, darkened = 0, masked = 0;
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x) {
                    const size_t i = size_t(y) * size_t(kW) + size_t(x);
                    if (f.objectId[i] == kNoObject || !NoSample(x, y) || Luminance(before[i].color) <= 0.0f) continue;
                    ++masked;
                    const PixelHistory now = HistoryAt(ref, two, i);
                    kept += now.length == before[i].length && now.color == before[i].color;
                    darkened += now.length > before[i].length && Luminance(now.color) < Luminance(before[i].color);
                }
            REQUIRE(masked > size_t(kW * kH / 4));
            CHECK(kept == (zeroAware ? masked : 0));
            CHECK(darkened == (zeroAware ? 0 : masked));
        }
    }
    CHECK(variants == 3);  // svgf, asvgf, asvgf-antilag
}

TEST_CASE("a disoccluded pixel without a sample holds nothing and its neighbours fill it",
          "[zero_samples]") {
    for (const char* name : {"svgf-weighted", "two-history", "two-history-asvgf-stable-antilag", "svgf", "asvgf"}) {
        INFO(name);
        const DenoiserVariant& variant = FindDenoiserVariant(name);
        DenoiserParams params = ParamsForDenoiser(name, DenoiserParams{});
        params.sampleCountsMayBeZero = true;
        SvgfFamilyReferenceDenoiser ref(variant, params);
        Plane<vec3> out;
        ref.Denoise(StillFrame(0, 2), out);
        FrameInputs f = StillFrame(1, 2);
        // One pixel of a surface, disoccluded and without a sample: nothing to keep, nothing new.
        int px = -1, py = -1;
        for (int y = 4; y < kH - 4 && px < 0; ++y)
            for (int x = 4; x < kW - 4 && px < 0; ++x)
                if (f.objectId(x, y) != kNoObject && f.objectId(x - 1, y) == f.objectId(x, y) &&
                    f.objectId(x + 1, y) == f.objectId(x, y))
                    px = x, py = y;
        REQUIRE(px >= 0);
        f.prevPixel(px, py) = vec2(-1.0f);
        f.sampleCount(px, py) = 0;
        f.direct(px, py) = f.indirect(px, py) = vec3(0.0f);
        ref.Denoise(f, out);
        CheckHistoriesFinite(ref, variant.family == DenoiserFamily::TwoHistory);
        const float length = variant.family == DenoiserFamily::TwoHistory
                                 ? ref.CurrentState().wu(px, py)
                                 : ref.CurrentHistory(0).length(px, py);
        CHECK(length == 0.0f);
        // Filled from its neighbours: the surface's illumination, not black, and finite.
        const vec3 filled = vec3(ref.Filtered(0)(px, py));
        INFO("filtered illumination " << filled.x << " " << filled.y << " " << filled.z);
        CHECK(std::isfinite(filled.x));
        CHECK(Luminance(filled) > 0.05f);
        CHECK(std::isfinite(out(px, py).x));
    }
}

TEST_CASE("no NaN or Inf in any history after frames with zero-sample pixels", "[zero_samples]") {
    for (Precision precision : {Precision::Fp32, Precision::Fp16})
        for (const DenoiserVariant& variant : DenoiserVariants()) {
            if (variant.family == DenoiserFamily::Rae) continue;
            const std::string name(variant.name);
            INFO(name << (precision == Precision::Fp16 ? " fp16" : " fp32"));
            DenoiserParams params = ParamsForDenoiser(name, DenoiserParams{});
            params.precision = precision;
            params.sampleCountsMayBeZero = true;
            SvgfFamilyReferenceDenoiser ref(variant, params);
            Plane<vec3> out;
            for (uint32_t frame = 0; frame < 5; ++frame) {
                ref.Denoise(
                    test::WithZeroSamples(test::RandomTwoHistoryFrame(kW, kH, frame), frame), out);
                CheckHistoriesFinite(ref, variant.family == DenoiserFamily::TwoHistory);
                REQUIRE(AllFinite(out));
            }
        }
}

// Bytes of one eye's buffers at 1280×720 (`fovrt memory`), fp32 / fp16 storage, as they are
// without the switch: a pixel without a sample needs no plane of its own.
TEST_CASE("accepting zero-sample pixels leaves every variant's memory plan unchanged",
          "[zero_samples]") {
    struct Expected {
        const char* name;
        size_t fp32, fp16;
    };
    const Expected expected[] = {
        {"svgf", 256393256, 153174056},
        {"svgf-weighted", 272982056, 162390056},
        {"asvgf", 268690856, 169158056},
        {"two-history", 385417256, 215842856},
        {"two-history-asvgf", 397714856, 231826856},
        {"asvgf-antilag", 268690856, 169158056},
        {"two-history-asvgf-antilag", 397714856, 231826856},
        {"two-history-stable", 407535656, 230588456},
        {"two-history-stable-firefly", 407535656, 230588456},
        {"two-history-stable-antilag", 407535656, 230588456},
        {"two-history-asvgf-stable-antilag", 419833256, 246572456},
        {"two-history-clamp", 385417256, 215842856},
        {"two-history-stable-clamp", 407535656, 230588456},
        {"two-history-hysteresis", 400162856, 226902056},
        {"two-history-stable-hysteresis", 414908456, 234274856},
        {"two-history-asvgf-stable-hysteresis", 427206056, 250258856},
        {"rae", 383804044, 200543724},
        {"rae-spp", 387572652, 202428172},
    };
    for (const Expected& e : expected) {
        INFO(e.name);
        for (Precision precision : {Precision::Fp32, Precision::Fp16}) {
            DenoiserParams params = ParamsForDenoiser(e.name, DenoiserParams{});
            params.precision = precision;
            CHECK(TotalBytes(PlanDenoiserMemory(e.name, 1280, 720, params)) ==
                  (precision == Precision::Fp32 ? e.fp32 : e.fp16));
        }
    }
    CHECK(std::size(expected) == DenoiserVariants().size());
}

// With the spp map able to hold zeros, svgf, asvgf and asvgf-antilag upload the sample counts:
// 2 B/pixel of plane (padded to whole words; 1280×720: 1,843,200 bytes over the table above; the
// staging ring, full at this size, does not grow). Every other variant reads
// them anyway or not at all (the RAE), so its plan is the one without the switch.
TEST_CASE("sampleCountsMayBeZero adds the sample-count plane to svgf, asvgf and asvgf-antilag only",
          "[zero_samples]") {
    struct Expected {
        const char* name;
        size_t fp32, fp16;
    };
    const Expected expected[] = {
        {"svgf", 258236456, 155017256},
        {"asvgf", 270534056, 171001256},
        {"asvgf-antilag", 270534056, 171001256},
    };
    auto total = [](const std::string& name, Precision precision, bool zeroAware) {
        DenoiserParams params = ParamsForDenoiser(name, DenoiserParams{});
        params.precision = precision;
        params.sampleCountsMayBeZero = zeroAware;
        return TotalBytes(PlanDenoiserMemory(name, 1280, 720, params));
    };
    auto plansSampleCounts = [](const std::string& name, bool zeroAware) {
        DenoiserParams params = ParamsForDenoiser(name, DenoiserParams{});
        params.sampleCountsMayBeZero = zeroAware;
        for (const PlanePlacement& p : BuildDenoiserPlan(name, params, 64, 64).planes)
            if (p.key.id.kind == PlaneKind::SampleCount) return true;
        return false;
    };
    for (const Expected& e : expected) {
        INFO(e.name);
        CHECK(total(e.name, Precision::Fp32, true) == e.fp32);
        CHECK(total(e.name, Precision::Fp16, true) == e.fp16);
        CHECK(total(e.name, Precision::Fp32, true) - total(e.name, Precision::Fp32, false) == 2u * 1280u * 720u);
        CHECK(plansSampleCounts(e.name, true));
        CHECK_FALSE(plansSampleCounts(e.name, false));
    }
    size_t others = 0;
    for (const DenoiserVariant& variant : DenoiserVariants()) {
        const std::string name(variant.name);
        if (ReadsCountsOnlyForZeros(variant)) continue;
        INFO(name);
        ++others;
        for (Precision precision : {Precision::Fp32, Precision::Fp16})
            CHECK(total(name, precision, true) == total(name, precision, false));
    }
    CHECK(others + std::size(expected) == DenoiserVariants().size());
}
