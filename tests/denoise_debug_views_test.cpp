// Debug views (denoise/debug_views.h): every variant offers the views its row's flags call for, on
// both backends; each view of the last frame lies in its valid range; unknown names, another
// variant's views and reads before the first frame (or after Reset) return false; A-SVGF's α is
// (1 − λ̂)α + λ̂ and two-history-asvgf's q is λ̂; and on Vulkan every view of every variant equals
// the C++ reference's within the tolerance of the pass that writes it (random 64×64 frames with
// sample counts and gradient samples, fp32 and fp16 histories, zero validation errors); the
// two-history family's history choice t is p + q − pq.
// Tolerance (as tests/denoise_svgf_vulkan_test.cpp and denoise_two_history_vulkan_test.cpp):
// |vk − ref| ≤ 2e-3·(1 + |ref|), fp16 histories 1e-2; SVGF's history length everywhere, the
// two-history family's planes for ≥ 99.5 % of the pixels (lavapipe's exp/pow differ from libm in
// the last bits, so a few taps near a threshold may flip).
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "denoise/debug_views.h"
#include "denoise/denoiser_factory.h"
#include "denoise/variants.h"
#include "denoise_svgf_scenes.h"
#include "test_support.h"
#include "vk/context.h"
#include "vk_test_support.h"

using namespace fovrt;
using fovrt::test::RandomTwoHistoryFrame;
using fovrt::test::TestContext;

namespace {

const DebugView& Row(std::string_view name) {
    for (const DebugView& view : DebugViewTable())
        if (view.name == name) return view;
    FAIL("no debug view " << std::string(name));
    return DebugViewTable().front();
}

// Every pixel finite and inside the view's valid range.
void CheckRange(const std::string& what, const std::string& name, const Plane<float>& plane) {
    const DebugView& row = Row(name);
    size_t outside = 0;
    float lo = INFINITY, hi = -INFINITY;
    for (float v : plane.vector()) {
        outside += !std::isfinite(v) || v < row.lo || v > row.hi;
        lo = std::min(lo, v), hi = std::max(hi, v);
    }
    INFO(what << " view " << name << ": values in [" << lo << ", " << hi << "], valid [" << row.lo
              << ", " << row.hi << "]");
    CHECK(outside == 0);
}

std::unique_ptr<Denoiser> Make(const std::string& name, const DenoiserParams& params, bool vulkan) {
    return vulkan ? CreateDenoiser(name, "vulkan", params, TestContext().get())
                  : CreateDenoiser(name, "cpu", params);
}

// A name no variant offers, a view of another variant, and no frame yet: false, `out` untouched.
void CheckRefusals(Denoiser& d, bool beforeFirstFrame) {
    Plane<float> out(2, 1, 7.0f);
    CHECK_FALSE(d.ReadDebugView("no-such-view", out));
    CHECK_FALSE(d.ReadDebugView("", out));
    const std::vector<std::string> offered = d.DebugViews();
    for (const DebugView& view : DebugViewTable()) {
        const bool isOffered =
            std::find(offered.begin(), offered.end(), view.name) != offered.end();
        if (!isOffered || beforeFirstFrame) {
            INFO(d.Name() << " " << d.Backend() << ": view " << std::string(view.name));
            CHECK_FALSE(d.ReadDebugView(std::string(view.name), out));
        }
    }
    CHECK(out.width() == 2);
    CHECK(out[0] == 7.0f);
}

}  // namespace

TEST_CASE("each variant offers the debug views of the passes its row runs", "[debug_views]") {
    const std::map<std::string, std::vector<std::string>> expected = {
        {"svgf", {"historyLength"}},
        {"svgf-weighted", {"historyLength", "historySamples"}},
        {"asvgf", {"historyLength", "alpha", "lambda"}},
        {"two-history", {"historyLength", "historySamples", "p", "q", "t", "historyU", "historyW", "variance"}},
        {"two-history-asvgf",
         {"historyLength", "historySamples", "alpha", "lambda", "p", "q", "t", "historyU", "historyW", "variance"}},
        {"asvgf-antilag", {"historyLength", "antilag", "lambda"}},
        {"two-history-asvgf-antilag",
         {"historyLength", "historySamples", "antilag", "lambda", "p", "q", "t", "historyU", "historyW", "variance"}},
        {"two-history-stable",
         {"historyLength", "historySamples", "p", "q", "t", "historyU", "historyW", "variance", "stableLum"}},
        {"two-history-stable-firefly",
         {"historyLength", "historySamples", "p", "q", "t", "historyU", "historyW", "variance", "stableLum"}},
        {"two-history-stable-antilag",
         {"historyLength", "historySamples", "p", "q", "t", "historyU", "historyW", "variance", "stableLum"}},
        {"two-history-asvgf-stable-antilag",
         {"historyLength", "historySamples", "antilag", "lambda", "p", "q", "t", "historyU", "historyW", "variance",
          "stableLum"}},
        {"two-history-clamp", {"historyLength", "historySamples", "q", "historyU", "historyW", "variance"}},
        {"two-history-stable-clamp", {"historyLength", "historySamples", "q", "historyU", "historyW", "variance", "stableLum"}},
        {"two-history-hysteresis",
         {"historyLength", "historySamples", "p", "q", "t", "historyU", "historyW", "variance"}},
        {"two-history-stable-hysteresis",
         {"historyLength", "historySamples", "p", "q", "t", "historyU", "historyW", "variance", "stableLum"}},
        {"two-history-asvgf-stable-hysteresis",
         {"historyLength", "historySamples", "antilag", "lambda", "p", "q", "t", "historyU", "historyW", "variance",
          "stableLum"}},
        {"rae", {}},      // a network's hidden state has no per-pixel meaning to show
        {"rae-spp", {}},
    };
    REQUIRE(expected.size() == DenoiserVariants().size());
    std::set<std::string> names, used;
    for (const DebugView& view : DebugViewTable()) {
        CHECK(names.insert(std::string(view.name)).second);  // declared once
        CHECK(view.lo <= view.hi);
        CHECK(!view.meaning.empty());
    }
    DenoiserParams params;
    for (const DenoiserVariant& v : DenoiserVariants()) {
        const std::string name(v.name);
        INFO(name);
        CHECK(DebugViewNames(v) == expected.at(name));
        CHECK(Make(name, params, false)->DebugViews() == expected.at(name));
        for (const std::string& view : DebugViewNames(v)) {
            used.insert(view);
            CHECK(FindDebugView(v, view) != nullptr);
        }
        CHECK(FindDebugView(v, "no-such-view") == nullptr);
    }
    CHECK(used == names);  // every view is offered by some variant
}

TEST_CASE("C++ reference debug views: valid ranges, refusals, A-SVGF's alpha and q",
          "[debug_views]") {
    DenoiserParams params;
    for (const DenoiserVariant& v : DenoiserVariants()) {
        const std::string name(v.name);
        INFO(name);
        auto d = Make(name, params, false);
        CheckRefusals(*d, true);
        Plane<vec3> out;
        for (uint32_t frame = 0; frame < 3; ++frame) {
            d->Denoise(RandomTwoHistoryFrame(40, 28, frame), out);
            for (const std::string& view : d->DebugViews()) {
                Plane<float> plane;
                REQUIRE(d->ReadDebugView(view, plane));
                CHECK(plane.width() == 40);
                CHECK(plane.height() == 28);
                CheckRange("cpu frame " + std::to_string(frame), view, plane);
            }
            CheckRefusals(*d, false);
            if (v.asvgfGradient) {  // α_i = (1 − λ̂)α + λ̂ (anti-lag: a = clamp(gain·λ̂, 0, 1)), pixel by pixel
                Plane<float> alpha, lambda;
                REQUIRE(d->ReadDebugView(v.antilag ? "antilag" : "alpha", alpha));
                REQUIRE(d->ReadDebugView("lambda", lambda));
                float maxDiff = 0.0f;
                for (size_t i = 0; i < alpha.size(); ++i) {
                    const float expected = v.antilag ? std::clamp(params.asvgf.antilagGain * lambda[i], 0.0f, 1.0f)
                                                     : (1.0f - lambda[i]) * params.asvgf.alpha + lambda[i];
                    maxDiff = std::max(maxDiff, std::abs(alpha[i] - expected));
                }
                CHECK(maxDiff < 1e-6f);
                if (v.twoHistory) {  // two-history-asvgf blends with q = λ̂
                    Plane<float> q;
                    REQUIRE(d->ReadDebugView("q", q));
                    CHECK(q.vector() == lambda.vector());
                }
            }
        }
        if (v.twoHistory && !v.clampHistory) {  // the history choice is the blend's t = p + q − pq, pixel by pixel
            Plane<float> p, q, t;
            REQUIRE(d->ReadDebugView("p", p));
            REQUIRE(d->ReadDebugView("q", q));
            REQUIRE(d->ReadDebugView("t", t));
            float maxDiff = 0.0f;
            for (size_t i = 0; i < t.size(); ++i) maxDiff = std::max(maxDiff, std::abs(t[i] - (p[i] + q[i] - p[i] * q[i])));
            CHECK(maxDiff < 1e-6f);
        }
        // After 3 frames with random sample counts the views vary over the image.
        for (const std::string& view : d->DebugViews()) {
            Plane<float> plane;
            REQUIRE(d->ReadDebugView(view, plane));
            const auto [lo, hi] = std::minmax_element(plane.vector().begin(), plane.vector().end());
            INFO(view << " in [" << *lo << ", " << *hi << "]");
            CHECK(*lo < *hi);
            // Random gradient samples are large changes everywhere: the anti-lag variants restart
            // their histories on them (what they are for), so only the others grow them.
            if (view == "historyLength" && !v.antilag) CHECK(*hi > 2.5f);
        }
        d->Reset();
        CheckRefusals(*d, true);
    }
}

TEST_CASE("vulkan debug views equal the C++ reference's", "[vulkan][debug_views]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto run = [](const DenoiserParams& params) {
        const bool half = params.precision == Precision::Fp16;
        const double tol = half ? 1e-2 : 2e-3;
        for (const DenoiserVariant& v : DenoiserVariants()) {
            const std::string name(v.name);
            auto vk = Make(name, params, true);
            auto ref = Make(name, params, false);
            REQUIRE(vk->Backend() == "vulkan");
            REQUIRE(vk->DebugViews() == ref->DebugViews());
            CheckRefusals(*vk, true);
            Plane<vec3> outVk, outRef;
            for (uint32_t frame = 0; frame < 4; ++frame) {
                const FrameInputs f = RandomTwoHistoryFrame(64, 64, frame);
                vk->Denoise(f, outVk);
                ref->Denoise(f, outRef);
                for (const std::string& view : vk->DebugViews()) {
                    Plane<float> a, b;
                    REQUIRE(vk->ReadDebugView(view, a));
                    REQUIRE(ref->ReadDebugView(view, b));
                    REQUIRE(a.size() == b.size());
                    size_t bad = 0;
                    double maxRel = 0.0;
                    for (size_t i = 0; i < a.size(); ++i) {
                        double rel = std::abs(double(a[i]) - b[i]) / (1.0 + std::abs(double(b[i])));
                        if (!std::isfinite(a[i])) rel = INFINITY;
                        maxRel = std::max(maxRel, rel);
                        bad += rel > tol;
                    }
                    const std::string what =
                        name + (half ? " fp16" : " fp32") + " frame " + std::to_string(frame);
                    INFO(what << " view " << view << ": max rel " << maxRel << ", " << bad << "/"
                              << a.size() << " beyond " << tol);
                    if (v.family == DenoiserFamily::Svgf)
                        CHECK(bad == 0);
                    else
                        CHECK(double(bad) <= 0.005 * double(a.size()));
                    CheckRange("vulkan " + what, view, a);
                }
                CheckRefusals(*vk, false);
            }
            vk->Reset();
            CheckRefusals(*vk, true);
        }
    };
    DenoiserParams params;
    SECTION("fp32 histories") { run(params); }
    SECTION("fp16 histories") {
        if (!TestContext()->supports16BitStorage()) FOVRT_SKIP("no 16-bit storage");
        params.precision = Precision::Fp16;
        run(params);
    }
    CHECK(TestContext()->validationErrors() == 0);
}
