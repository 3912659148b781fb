// The transient pool (denoise/transient_pool.h): every variant's plan shares memory only between
// planes never live at once, and the validator rejects plans that share it otherwise. The Vulkan
// tests against the C++ reference (denoise_svgf_vulkan_test, denoise_two_history_vulkan_test)
// run on the aliased buffers.
#include <catch2/catch.hpp>

#include <climits>
#include <string>
#include <utility>

#include "denoise/pass_plan.h"
#include "denoise/transient_pool.h"
#include "denoise/variants.h"

using namespace fovrt;

namespace {
const PlanePlacement& Find(const DenoiserPlan& plan, const std::string& name) {
    for (const PlanePlacement& p : plan.planes)
        if (BufferName(p.key) == name) return p;
    FAIL("no plane " << name);
    return plan.planes.front();
}
PlanePlacement& Find(DenoiserPlan& plan, const std::string& name) {
    return const_cast<PlanePlacement&>(Find(std::as_const(plan), name));
}
}  // namespace

TEST_CASE("every variant's transient pool shares memory only between planes never live at once") {
    for (const std::string& name : DenoiserNames())
        for (bool combined : {false, true})
            for (int iterations : {0, 1, 5}) {
                DenoiserParams p;
                p.svgf.filterCombined = combined;
                p.svgf.atrousIterations = iterations;
                p.svgf.feedbackIteration = iterations > 0 ? 1 : 0;
                INFO(name << (combined ? " combined" : " separate") << " iterations " << iterations);
                const DenoiserPlan plan = BuildDenoiserPlan(name, p, 40, 24);
                CHECK(AliasingConflict(plan) == "");
            }
}

TEST_CASE("the pool shares: the illumination ping-pong of both channels and the output fold into few slots") {
    const DenoiserPlan plan = BuildDenoiserPlan("two-history", DenoiserParams{}, 64, 64);
    size_t slots = 0, pooled = 0;
    for (const BufferPlan& b : plan.buffers) slots += b.transient ? 1 : 0;
    for (const PlanePlacement& p : plan.planes) pooled += plan.buffers[p.allocation].transient ? 1 : 0;
    CHECK(slots > 0);
    CHECK(pooled > slots);
    // Histories, and planes that carry a value into the next frame, keep their own buffers.
    for (const char* permanent : {"direct.color.A", "direct.color.B", "geometry.depth.A", "stats"})
        CHECK_FALSE(plan.buffers[Find(plan, permanent).allocation].transient);
    const DenoiserPlan asvgf = BuildDenoiserPlan("asvgf", DenoiserParams{}, 64, 64);
    CHECK_FALSE(asvgf.buffers[Find(asvgf, "asvgf.alpha").allocation].transient);  // the reset's 1 until a previous frame
}

TEST_CASE("the validator rejects two live planes in one allocation, and a history in the pool") {
    const DenoiserPlan good = BuildDenoiserPlan("two-history", DenoiserParams{}, 64, 64);
    REQUIRE(AliasingConflict(good) == "");

    // Both ping-pong planes of a channel are live in the à-trous iterations.
    DenoiserPlan live = good;
    Find(live, "direct.illum1").allocation = Find(live, "direct.illum0").allocation;
    const std::string overlap = AliasingConflict(live);
    CHECK(overlap.find("direct.illum0") != std::string::npos);
    CHECK(overlap.find("direct.illum1") != std::string::npos);
    CHECK(overlap.find("while both are live") != std::string::npos);

    // q is read by the blend while the guide is still read by à-trous.
    DenoiserPlan guide = good;
    Find(guide, "q").allocation = Find(guide, "geometry.guide").allocation;
    CHECK(AliasingConflict(guide) != "");

    // A history holds its value into the next frame: it never shares.
    DenoiserPlan history = good;
    Find(history, "direct.illum0").allocation = Find(history, "direct.moments.A").allocation;
    CHECK(AliasingConflict(history).find("holds a value across frames") != std::string::npos);

    // What the host reads after the frame (the download, the q debug view) lives to its end.
    for (const char* read : {"output", "q"}) {
        const PlaneLifetime life = PlaneLifetimes(good).at(Find(good, read).key);
        CHECK(life.transient);
        CHECK(life.last == INT_MAX);
    }
}
