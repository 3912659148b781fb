// The denoiser benchmark machinery on a small image (the full 1280×720 run is the hidden test
// "[.bench]": `denoise_svgf_bench_test "[.bench]"`, or `fovrt bench --denoisers`).
#include "denoise/denoise_bench.h"
#include "test_support.h"
#include "vk/context.h"

using namespace fovrt;

TEST_CASE("bytes per pixel of the SVGF passes", "[svgf]") {
    DenoiserParams p;
    auto passes = SvgfPassBytes(p);
    REQUIRE(passes.size() == 1 + 1 + 1 + 5 + 1 + 1);
    CHECK(passes[1].pass == "reproject");
    // Reprojection, both channels in one pass: geometry of both frames 2·20 B, gradient and motion
    // 16 B once; per channel colour 12 B, fp32 history read 24 B and write 12 B (no colour: the
    // à-trous feedback writes it), illumination 16 B.
    CHECK(passes[1].bytesPerPixel == Approx(56 + 2 * (12 + 24 + 12 + 16)));
    // One à-trous iteration, both channels in one pass: per channel illum in/out 32 B, once
    // geometry 20 B + gradient 8 B; iteration 0 also writes each fp32 colour history (12 B).
    CHECK(passes[3].bytesPerPixel == Approx(2 * (32 + 12) + 20 + 8));
    CHECK(passes[4].bytesPerPixel == Approx(2 * 32 + 20 + 8));
    p.svgf.filterCombined = true;
    CHECK(SvgfPassBytes(p)[4].bytesPerPixel == Approx(32 + 20 + 8));
    p.svgf.filterCombined = false;
    p.precision = Precision::Fp16;
    CHECK(SvgfPassBytes(p)[1].bytesPerPixel < passes[1].bytesPerPixel);
}

TEST_CASE("denoiser bench reports every pass", "[svgf]") {
    DenoiserBenchOptions o;
    o.denoisers = {"svgf", "svgf-weighted"};
    o.width = 64;
    o.height = 48;
    o.frames = 1;
    o.warmup = 1;
    auto report = RunDenoiserBench(o);
    CHECK(report.memcpyGBps > 0.1);
    size_t expected = VulkanContext::Available() ? 4 : 2;
    REQUIRE(report.results.size() == expected);
    for (const auto& r : report.results) {
        CHECK(r.passes.size() >= 7);
        CHECK(r.bytesPerPixel > 100.0);
        CHECK(r.computeMs > 0.0);
        CHECK(r.boundMs > 0.0);
    }
}

TEST_CASE("denoiser bench at 1280x720", "[.bench]") {
    DenoiserBenchOptions o;
    o.denoisers = {"svgf", "svgf-weighted"};
    RunDenoiserBench(o);
}

TEST_CASE("denoiser bench at 640x360", "[.bench]") {
    DenoiserBenchOptions o;
    o.denoisers = {"svgf"};
    o.width = 640;
    o.height = 360;
    RunDenoiserBench(o);
}
