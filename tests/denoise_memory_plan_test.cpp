// The memory plan (denoise/memory_plan.h): staging as large as the transfers need.
#include <catch2/catch.hpp>

#include <string>

#include "denoise/gradient_strata.h"
#include "denoise/memory_plan.h"
#include "denoise/pass_plan.h"
#include "denoise/variants.h"

using namespace fovrt;

namespace {
size_t Bytes(const DenoiserPlan& plan, const std::string& name) {
    for (const BufferPlan& b : plan.buffers)
        if (b.name == name) return b.bytes;
    return 0;
}
}  // namespace

TEST_CASE("staging holds what the host writes, and the downloads reuse its room") {
    const int w = 40, h = 24;
    const size_t pixels = size_t(w) * size_t(h);
    // Every frame uploads direct, indirect, modulation, emission (4 × 12 B), the depth gradient and
    // the previous pixel (2 × 8 B), this frame's normal, depth and object id (12 + 4 + 4 B), then
    // downloads the 12 B output and the counters into the same room.
    const size_t uploads = pixels * (4 * 12 + 2 * 8 + 12 + 4 + 4);
    for (const char* name : {"svgf", "two-history"})
        CHECK(Bytes(BuildDenoiserPlan(name, DenoiserParams{}, w, h), "staging") == uploads);
    // The two-history family stages its sample counts apart, and only what it uploads: A-SVGF's
    // gradient samples only where the variant reads them.
    const size_t counts = StagingAlign(PlaneBytes(PlaneKind::SampleCount, {w, h}));
    const size_t samples = StagingAlign(GradientSampleCapacity(w, h) * sizeof(GradientSample));
    CHECK(Bytes(BuildDenoiserPlan("two-history", DenoiserParams{}, w, h), "staging.extra") == counts);
    CHECK(Bytes(BuildDenoiserPlan("two-history-asvgf", DenoiserParams{}, w, h), "staging.extra") == counts + samples);
}
