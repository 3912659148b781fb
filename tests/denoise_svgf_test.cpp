// SVGF (C++ reference backend; the same checks run on Vulkan in denoise_svgf_vulkan_test):
// closed-form reprojection taps, interpolated history length, disocclusion, off-screen, camera
// cuts, NaN sanitising, weighted accumulation, convergence, and the paper's Fig. 9 property.
#include <cmath>

#include "core/error.h"
#include "denoise/denoiser_factory.h"
#include "denoise/memory_plan.h"
#include "denoise/reference/svgf_family_ref.h"
#include "denoise/reference/svgf_ref.h"
#include "denoise_svgf_scenes.h"
#include "test_support.h"

using namespace fovrt;
using namespace fovrt::test;

namespace {
DenoiserParams Params(int iterations = 5) {
    DenoiserParams p;
    p.svgf.atrousIterations = iterations;
    return p;
}
// SVGF's reprojection run frame by frame on one 64×64 static frame (its pixels changed by the
// test between steps), with two history sides and the previous geometry.
struct ReprojectBench {
    FrameInputs frame = StaticScene{}.Frame(0);
    SvgfGeometryPlanes prev;
    SvgfHistory history[2];
    Plane<vec4> illum;
    DenoiseStats stats;

    explicit ReprojectBench(bool weighted) {
        prev.Allocate(64, 64);
        for (SvgfHistory& h : history) h.Allocate(64, 64, weighted);
    }
    // Frame t: reads history side (t + 1) & 1, writes side t & 1.
    void Step(int t, const SvgfReprojectOptions& options) {
        SvgfReprojectRef(frame.direct, nullptr, frame, prev.View(), history[(t + 1) & 1], history[t & 1], illum,
                         options, stats);
        prev.CopyFrom(frame);
    }
};

}  // namespace

TEST_CASE("reprojection taps: bilinear weights, renormalisation, 3x3 fallback, off-screen", "[svgf]") {
    StaticScene scene;
    FrameInputs f = scene.Frame(0);
    SvgfGeometryPlanes prev;
    prev.CopyFrom(f);
    const int x = 10, y = 20;  // inside object 1
    f.prevPixel(x, y) = vec2(x + 0.5f + 0.25f, y + 0.5f);
    ReprojectionTaps taps = FindReprojectionTaps(f, prev.View(), x, y);
    REQUIRE(taps.count == 2);  // the two taps with zero bilinear weight are skipped
    CHECK(taps.index[0] == y * 64 + x);
    CHECK(taps.weight[0] == Approx(0.75f));
    CHECK(taps.weight[1] == Approx(0.25f));

    // The right tap belongs to another object: dropped, the left one renormalised to 1.
    prev.objectId(x + 1, y) = 2;
    taps = FindReprojectionTaps(f, prev.View(), x, y);
    REQUIRE(taps.count == 1);
    CHECK(taps.weight[0] == Approx(1.0f));

    // Depth test: |z_prev − z| / (dz + 0.01) > 10 rejects (dz = 0.01 here → 0.2 m).
    prev.objectId(x + 1, y) = 1;
    prev.depth(x, y) += 0.25f;
    prev.depth(x + 1, y) += 0.25f;
    prev.depth(x, y + 1) += 0.1f;  // within tolerance: a 3×3 fallback tap
    taps = FindReprojectionTaps(f, prev.View(), x, y);
    REQUIRE(taps.count == 7);  // 3×3 around the nearest pixel (x, y) minus the two rejected
    CHECK(taps.weight[0] == Approx(1.0f / 7.0f));

    // Off-screen and NaN motion: no taps (disocclusion).
    f.prevPixel(x, y) = vec2(-5.0f, 3.0f);
    CHECK(FindReprojectionTaps(f, prev.View(), x, y).count == 0);
    f.prevPixel(x, y) = vec2(std::nanf(""), 3.0f);
    CHECK(FindReprojectionTaps(f, prev.View(), x, y).count == 0);
}

TEST_CASE("history length is interpolated from the valid taps, not the nearest", "[svgf]") {
    StaticScene scene;
    FrameInputs f = scene.Frame(0);
    SvgfGeometryPlanes prev;
    prev.CopyFrom(f);
    SvgfHistory histPrev, histCur;
    histPrev.Allocate(64, 64, false);
    histCur.Allocate(64, 64, false);
    const int x = 10, y = 20;
    histPrev.length(x, y) = 10.0f;
    histPrev.length(x + 1, y) = 2.0f;
    f.prevPixel(x, y) = vec2(x + 1.0f, y + 0.5f);  // halfway between the two centres
    Plane<vec4> illum;
    DenoiseStats stats;
    SvgfReprojectRef(f.direct, nullptr, f, prev.View(), histPrev, histCur, illum, {}, stats);
    CHECK(histCur.length(x, y) == Approx(6.0f + 1.0f));
}

TEST_CASE("temporal accumulation: alpha = max(alpha, 1/length), moments and variance", "[svgf]") {
    const float values[3] = {1.0f, 3.0f, 2.0f};
    ReprojectBench b(false);
    Plane<vec4>& illum = b.illum;
    const int x = 10, y = 20;
    float expect = 0.0f, m1 = 0.0f, m2 = 0.0f;
    for (int t = 0; t < 3; ++t) {
        b.frame.direct(x, y) = vec3(values[t]);
        b.Step(t, {});
        float a = std::max(0.2f, 1.0f / float(t + 1));
        expect = t == 0 ? values[0] : glm::mix(expect, values[t], a);
        m1 = t == 0 ? values[0] : glm::mix(m1, values[t], a);
        m2 = t == 0 ? values[0] * values[0] : glm::mix(m2, values[t] * values[t], a);
        CHECK(b.history[t & 1].length(x, y) == Approx(float(t + 1)));
    }
    CHECK(illum(x, y).x == Approx(expect));
    CHECK(illum(x, y).w == Approx(m2 - m1 * m1));
}

TEST_CASE("svgf-weighted: W <- (1-alpha) W + n, C <- C + n (x - C) / W", "[svgf]") {
    ReprojectBench b(true);
    SvgfReprojectOptions opt;
    opt.weighted = true;
    const int x = 10, y = 20;
    const float xs[3] = {1.0f, 4.0f, 2.0f};
    const uint16_t ns[3] = {4, 1, 8};
    float W = 0.0f, C = 0.0f;
    for (int t = 0; t < 3; ++t) {
        b.frame.direct(x, y) = vec3(xs[t]);
        b.frame.sampleCount(x, y) = ns[t];
        b.Step(t, opt);
        W = 0.8f * W + float(ns[t]);
        C = C + float(ns[t]) * (xs[t] - C) / W;
        CHECK(b.history[t & 1].weight(x, y) == Approx(W));
        CHECK(b.history[t & 1].color(x, y).x == Approx(C));
    }
}

TEST_CASE("a constant image is preserved exactly by every stage", "[svgf]") {
    StaticScene scene;
    auto d = CreateDenoiser("svgf", "cpu", Params());
    Plane<vec3> out;
    for (uint32_t t = 0; t < 3; ++t) {
        FrameInputs f = scene.Frame(t);
        d->Denoise(f, out);
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                vec3 expect = f.NoisyColor(x, y);
                REQUIRE(out(x, y).x == Approx(expect.x).margin(1e-5));
                REQUIRE(out(x, y).z == Approx(expect.z).margin(1e-5));
            }
    }
    CHECK(d->Backend() == "cpu");
    CHECK(d->LastTimings().size() == 2 + 5 + 1);
}

TEST_CASE("disocclusion, camera cut and NaN inputs never leave stale or non-finite history", "[svgf]") {
    StaticScene scene;
    scene.sigma = [](int, int) { return 0.3f; };
    SvgfFamilyReferenceDenoiser d(FindDenoiserVariant("svgf"), Params(2));
    Plane<vec3> out;
    for (uint32_t t = 0; t < 6; ++t) d.Denoise(scene.Frame(t), out);
    CHECK(d.CurrentHistory(0).length(10, 20) == Approx(6.0f));
    CHECK(d.CurrentHistory(0).length(10, 2) == Approx(1.0f));  // background never accumulates

    // Object id changes in a block → history 1 there, kept elsewhere; a NaN, an Inf, a negative.
    FrameInputs f = FaultyFrame(scene, 6);
    d.Denoise(f, out);
    CHECK(d.CurrentHistory(0).length(11, 11) == Approx(1.0f));
    CHECK(d.CurrentHistory(0).length(20, 40) == Approx(7.0f));
    CHECK(d.Stats().nonFiniteSamples == 2);
    CHECK(d.Stats().negativeSamples == 1);
    for (size_t c = 0; c < d.ChannelCount(); ++c)
        for (size_t i = 0; i < out.size(); ++i) {
            REQUIRE(IsFinite(d.CurrentHistory(c).color[i]));
            REQUIRE(std::isfinite(d.CurrentHistory(c).moments[i].x));
            REQUIRE(std::isfinite(d.CurrentHistory(c).moments[i].y));
        }
    for (size_t i = 0; i < out.size(); ++i) REQUIRE(IsFinite(out[i]));

    // Off-screen reprojection: everything moved 100 px → disocclusion everywhere.
    f = scene.Frame(7);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) f.prevPixel(x, y) += vec2(100.0f, 0.0f);
    d.Denoise(f, out);
    CHECK(d.CurrentHistory(0).length(20, 40) == Approx(1.0f));

    // Parameter change: same path as Reset().
    DenoiserParams changed = Params(3);
    d.SetParams(changed);
    d.Denoise(scene.Frame(8), out);
    CHECK(d.CurrentHistory(0).length(20, 40) == Approx(1.0f));

    // Camera cut: no stale history.
    for (uint32_t t = 9; t < 13; ++t) d.Denoise(scene.Frame(t), out);
    CHECK(d.CurrentHistory(0).length(20, 40) == Approx(5.0f));  // frames 8–11
    f = scene.Frame(13);
    f.cameraCut = true;
    d.Denoise(f, out);
    CHECK(d.CurrentHistory(0).length(20, 40) == Approx(1.0f));
}

TEST_CASE("convergence: temporal error falls over 30 frames on a static scene", "[svgf]") {
    StaticScene scene;
    scene.sigma = [](int, int) { return 0.5f; };
    auto d = CreateDenoiser("svgf", "cpu", Params());
    Plane<vec3> out, prevOut, noisy(64, 64), prevNoisy;
    std::vector<float> errors;
    float noisyError = 0.0f;
    for (uint32_t t = 0; t < 30; ++t) {
        FrameInputs f = scene.Frame(t);
        d->Denoise(f, out);
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) noisy(x, y) = f.NoisyColor(x, y);
        if (t > 0) {
            errors.push_back(TemporalError(out, prevOut));
            noisyError += TemporalError(noisy, prevNoisy) / 29.0f;
        }
        prevOut = out;
        prevNoisy = noisy;
    }
    float early = (errors[0] + errors[1] + errors[2]) / 3.0f;
    float late = (errors[26] + errors[27] + errors[28]) / 3.0f;
    WARN("temporal error: noisy input " << noisyError << ", svgf frames 1-3: " << early
                                        << ", frames 27-29: " << late);
    CHECK(late < 0.75f * early);
    CHECK(late < 0.1f * noisyError);
}

// SVGF paper Fig. 9: a textured signal whose noise rises across the image. After enough history
// the temporal variance estimate stays low on the low-noise side, so the luminance weights keep
// its texture; a purely spatial estimate sees the texture as variance and blurs it.
TEST_CASE("Fig. 9: temporal variance keeps the low-noise side sharper than spatial variance", "[svgf]") {
    StaticScene scene;
    auto clean = [](int x, int) { return (x / 2) % 2 ? 2.0f : 0.5f; };  // 2-px stripes
    scene.direct = clean;
    scene.indirect = [](int, int) { return 0.0f; };
    scene.sigma = [](int x, int) { return 1.5f * float(x) / 64.0f; };
    auto run = [&](int threshold) {
        DenoiserParams p = Params();
        p.svgf.varianceHistoryThreshold = threshold;
        SvgfFamilyReferenceDenoiser d(FindDenoiserVariant("svgf"), p);
        Plane<vec3> out;
        for (uint32_t t = 0; t < 24; ++t) d.Denoise(scene.Frame(t, 5), out);
        // Error of demodulated direct vs clean, low-noise quarter (x < 16) of object 1 rows.
        double err = 0.0;
        int count = 0;
        for (int y = 8; y < 56; ++y)
            for (int x = 2; x < 14; ++x) {
                float v = d.Filtered(0)(x, y).x;
                err += std::abs(v - clean(x, y));
                ++count;
            }
        return err / count;
    };
    double temporal = run(4);
    double spatial = run(1 << 20);  // spatial estimate everywhere, every frame
    WARN("low-noise side mean abs error: temporal variance " << temporal << ", spatial " << spatial);
    CHECK(temporal < 0.7 * spatial);
}

TEST_CASE("memory plan lists A/B histories and budgets fail with the largest buffers", "[svgf]") {
    DenoiserParams p;
    auto plan = PlanDenoiserMemory("svgf", 64, 32, p);
    const size_t n = 64 * 32;
    // Histories: geometry 2×20 B + per channel 2×(12 + 8 + 4) B, two channels.
    CHECK(HistoryBytes(plan) == n * (2 * 20 + 2 * 2 * 24));
    // fp16: the normal octahedral (4 B), depth and object id one code (4 B), the channels'
    // histories in halves.
    p.precision = Precision::Fp16;
    CHECK(HistoryBytes(PlanDenoiserMemory("svgf", 64, 32, p)) == n * (2 * 8 + 2 * 2 * 12));
    auto weighted = PlanDenoiserMemory("svgf-weighted", 64, 32, DenoiserParams{});
    CHECK(HistoryBytes(weighted) == n * (2 * 20 + 2 * 2 * 28));
    CHECK_NOTHROW(EnforceMemoryBudget(plan, 0));
    try {
        EnforceMemoryBudget(plan, 1000);
        FAIL("expected fovrt::Error");
    } catch (const Error& e) {
        std::string what = e.what();
        CHECK(what.find("largest buffers") != std::string::npos);
        CHECK(what.find("staging") != std::string::npos);  // the host-visible copy of the transfers
    }
    CHECK_THROWS_AS(PlanDenoiserMemory("nope", 64, 32, p), Error);
    CHECK_THROWS_AS(CreateDenoiser("nope", "cpu", p), Error);
}
