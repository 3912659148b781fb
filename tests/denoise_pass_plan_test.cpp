// The pass plan (denoise/pass_plan.h) against the memory plan: the planes the passes use are
// exactly the planes allocated, for every variant and mode.
#include <catch2/catch.hpp>
#include <set>
#include <string>

#include "denoise/pass_plan.h"
#include "denoise/variants.h"

using namespace fovrt;

namespace {
// Memory-plan name without the history side.
std::string Unsided(const std::string& name) {
    for (const char* side : {".A", ".B"})
        if (name.size() > 2 && name.compare(name.size() - 2, 2, side) == 0)
            return name.substr(0, name.size() - 2);
    return name;
}
// Buffers no pass models: host-visible staging, and the few bytes of counters and dispatch
// arguments (their size does not scale with the image, so they move ~0 bytes per pixel).
bool ModelledByNoPass(const std::string& name) {
    return name.rfind("staging", 0) == 0 || name == "stats" ||
           name.find(".spatialArgs") != std::string::npos;
}
}  // namespace

TEST_CASE("every plane a pass uses is allocated, and every allocated plane is used") {
    for (const std::string& name : DenoiserNames())
        for (bool combined : {false, true})
            for (Precision precision : {Precision::Fp32, Precision::Fp16})
                for (int iterations : {0, 1, 5}) {
                    DenoiserParams p;
                    p.svgf.filterCombined = combined;
                    p.precision = precision;
                    p.svgf.atrousIterations = iterations;
                    p.svgf.feedbackIteration = iterations > 0 ? 1 : 0;
                    INFO(name << (combined ? " combined" : " separate") << " iterations "
                              << iterations);
                    const DenoiserPlan plan = BuildDenoiserPlan(name, p, 40, 24);
                    std::set<std::string> allocated, used;
                    for (const BufferPlan& b : plan.buffers) allocated.insert(Unsided(b.name));
                    for (const PlannedPass& pass : plan.passes)
                        for (const PlaneUse& use : pass.uses) {
                            INFO("pass " << pass.name);
                            CHECK(allocated.count(use.plane) == 1);
                            used.insert(use.plane);
                        }
                    for (const std::string& buffer : allocated)
                        if (!ModelledByNoPass(buffer)) {
                            INFO("buffer " << buffer);
                            CHECK(used.count(buffer) == 1);
                        }
                }
}

TEST_CASE(
    "pass order: A-SVGF's gradient before the guide, the blend right after a-trous iteration 0") {
    DenoiserParams p;
    const DenoiserPlan plan = BuildDenoiserPlan("two-history-asvgf", p, 32, 32);
    std::vector<std::string> names;
    for (const PlannedPass& pass : plan.passes) names.push_back(pass.name);
    const std::vector<std::string> expected = {"upload",
                                               "asvgf_gradient",
                                               "asvgf_alpha",
                                               "pack_guide",
                                               "two_history_reproject",
                                               "filter_moments",
                                               "atrous0",
                                               "two_history_blend",
                                               "atrous1",
                                               "atrous2",
                                               "atrous3",
                                               "atrous4",
                                               "modulate",
                                               "download"};
    CHECK(names == expected);
    // two-history keeps the EMA gradient pass; with no à-trous the blend follows the moments.
    p.svgf.atrousIterations = 0;
    p.svgf.feedbackIteration = 0;
    names.clear();
    for (const PlannedPass& pass : BuildDenoiserPlan("two-history", p, 32, 32).passes)
        names.push_back(pass.name);
    CHECK(names == std::vector<std::string>{"upload", "pack_guide", "two_history_reproject",
                                            "filter_moments", "two_history_gradient",
                                            "two_history_blend", "modulate", "download"});
}

TEST_CASE("variant rows are consistent: sample counts where a history weighs by them") {
    for (const DenoiserVariant& v : DenoiserVariants()) {
        INFO(v.name);
        if (v.family == DenoiserFamily::Rae) continue;  // no histories of the SVGF kind
        CHECK(v.needsSampleCount == (v.weightBySampleCount || v.twoHistory));
        CHECK(v.needsGradientSamples == v.asvgfGradient);
        if (v.twoHistory)
            CHECK(v.emaGradient != v.asvgfGradient);  // q comes from exactly one of them
        CHECK(!(v.emaGradient && !v.twoHistory));     // g feeds only the blend's q
        CHECK((v.family == DenoiserFamily::Svgf) == !(v.twoHistory || v.asvgfGradient));
    }
}
