// The denoiser benchmark machinery on a small image (the full 1280×720 run is the hidden test
// "[.bench]": `denoise_svgf_bench_test "[.bench]"`, or `fovrt bench --denoisers`).
#include "denoise/bench/denoise_bench.h"
#include "test_support.h"
#include "vk/context.h"

using namespace fovrt;

// The byte models themselves: denoise_pass_bytes_test.cpp.

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
    if (VulkanContext::Available()) CHECK(report.device.texelGBps > 0.0);
    for (const auto& r : report.results) {
        CHECK(r.passes.size() >= 7);
        CHECK(r.bytesPerPixel > 100.0);
        CHECK(r.computeMs > 0.0);
        CHECK(r.boundMs > 0.0);
        for (const auto& p : r.passes) CHECK(p.bytesPerPixel > 0.0);
        CHECK((r.deviceBoundMs > 0.0) == (r.backend == "vulkan"));
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
