// The run's memory plan (PlanRunMemory, app/denoiser_set.h) with the metric's luminance frames:
// a `run` with run.score holds, per eye, the reference's and every variant's luminance for every
// frame (4 bytes per pixel), and nothing of the kind without scoring or with metric.vdp off.
#include <catch2/catch.hpp>

#include <string>

#include "pipeline/denoiser_set.h"
#include "denoise/memory_plan.h"

using namespace fovrt;

namespace {

size_t VdpBytes(const std::vector<BufferPlan>& plan, size_t* buffers = nullptr) {
    size_t bytes = 0, count = 0;
    for (const BufferPlan& b : plan)
        if (b.name.find(".vdp.") != std::string::npos) bytes += b.bytes, ++count;
    if (buffers) *buffers = count;
    return bytes;
}

}  // namespace

TEST_CASE("run.score adds the metric's luminance frames to the run's memory plan", "[app][memory]") {
    RunConfig config;
    config.camera.width = 64;
    config.camera.height = 36;
    config.run.frames = 10;
    config.denoise.denoisers = {"svgf", "two-history"};
    const std::vector<BufferPlan> unscored = PlanRunMemory(config);
    CHECK(VdpBytes(unscored) == 0);

    config.run.score = true;
    const std::vector<BufferPlan> scored = PlanRunMemory(config);
    size_t buffers = 0;
    // Two eyes × (reference + two variants), each 64 × 36 pixels × 4 bytes × 10 frames.
    CHECK(VdpBytes(scored, &buffers) == 2 * 3 * 64 * 36 * 4 * 10);
    CHECK(buffers == 6);
    CHECK(TotalBytes(scored) == TotalBytes(unscored) + 2 * 3 * 64 * 36 * 4 * 10);
    CHECK(PlanVdpMemory(config, true).size() == 6);

    config.metric.vdp = false;  // nothing scored with the metric: nothing held for it
    CHECK(VdpBytes(PlanRunMemory(config)) == 0);
    CHECK(PlanVdpMemory(config, true).empty());
}
