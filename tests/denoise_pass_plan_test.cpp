// The pass plan (denoise/pass_plan.h) against the memory plan: the planes the passes use are
// exactly the planes allocated, for every variant and mode; and against the binding lists: every
// dispatch binds each slot of its shader's layout once, reading only what its kind lets it read.
#include <catch2/catch.hpp>
#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "denoise/mechanism_passes.h"
#include "denoise/pass_plan.h"
#include "denoise/plan_writer.h"
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
// Every mode the plans are checked in: separate and combined filtering, fp32 and fp16, and 0, 1
// and 5 à-trous iterations (feedback after the first where there is one).
template <typename Check>
void ForEachPlanMode(Check check) {
    for (bool combined : {false, true})
        for (Precision precision : {Precision::Fp32, Precision::Fp16})
            for (int iterations : {0, 1, 5}) {
                DenoiserParams p;
                p.svgf.filterCombined = combined;
                p.precision = precision;
                p.svgf.atrousIterations = iterations;
                p.svgf.feedbackIteration = iterations > 0 ? 1 : 0;
                INFO((combined ? "combined" : "separate") << " iterations " << iterations);
                check(p);
            }
}
}  // namespace

TEST_CASE("every plane a pass uses is allocated, and every allocated plane is used") {
    for (const std::string& name : DenoiserNames())
        ForEachPlanMode([&](const DenoiserParams& p) {
            INFO(name);
            const DenoiserPlan plan = BuildDenoiserPlan(name, p, 40, 24);
            std::set<std::string> allocated, used;
            // The SVGF family's planes (some share a transient slot); the RAE's buffers are its planes.
            for (const PlanePlacement& b : plan.planes) allocated.insert(Unsided(BufferName(b.key)));
            if (plan.planes.empty())
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
        });
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
    // A-SVGF keeps one history: its reprojection is timed as "reproject", as SVGF's, though the
    // two-history family's shader runs it.
    names.clear();
    for (const PlannedPass& pass : BuildDenoiserPlan("asvgf", DenoiserParams{}, 32, 32).passes)
        names.push_back(pass.name);
    CHECK(std::count(names.begin(), names.end(), "reproject") == 1);
    CHECK(std::count(names.begin(), names.end(), "two_history_reproject") == 0);
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
        CHECK(!(v.antilag && !v.asvgfGradient));      // anti-lag acts on A-SVGF's λ
        CHECK((v.family == DenoiserFamily::Svgf) == !(v.twoHistory || v.asvgfGradient));
    }
}

namespace {
// The kinds of a stage shader's layout (one channel or "_pair"), by slot, from its binding list.
#define FOVRT_TEST_KIND(pass, name, slot, kind, format, variable) kinds.at(size_t(slot)) = #kind;
#define FOVRT_TEST_KINDS(LIST)                                             \
    [] {                                                                   \
        std::vector<std::string> kinds(size_t(FOVRT_BINDING_COUNT(LIST))); \
        LIST(FOVRT_TEST_KIND)                                              \
        return kinds;                                                      \
    }()
std::vector<std::string> BindingKinds(StageShader shader, bool pair) {
#define FOVRT_TEST_SHADER(id, stem, list, pairList) \
    case StageShader::id:                           \
        return pair ? FOVRT_TEST_KINDS(pairList) : FOVRT_TEST_KINDS(list);
    switch (shader) { FOVRT_STAGE_SHADERS(FOVRT_TEST_SHADER) }
#undef FOVRT_TEST_SHADER
    return {};
}
// Whether a binding of `kind` may be used so: read-only kinds are never written, write-only never
// read (LIST slots are the pixel lists and their counters, appended to and read).
bool AccessFits(const std::string& kind, Access access) {
    if (access == Access::Unused || kind == "RW" || kind == "LIST") return true;
    if (kind == "WRITE") return access == Access::Write;
    return access == Access::Read;  // TEXEL, HTEXEL, HTEXEL3, UTEXEL, DTEXEL, OTEXEL, NTEXEL, READ
}
}  // namespace

TEST_CASE("every dispatch of every plan binds each slot of its layout once, as its kind allows") {
    for (const DenoiserVariant& v : DenoiserVariants()) {
        if (v.family == DenoiserFamily::Rae) continue;  // its own host
        ForEachPlanMode([&](const DenoiserParams& p) {
            for (const PlannedPass& pass : BuildDenoiserPlan(v.name, p, 40, 24).passes)
                for (const Command& command : pass.commands) {
                    const auto* d = std::get_if<DispatchCommand>(&command.op);
                    if (!d) continue;
                    const std::vector<std::string> kinds =
                        BindingKinds(d->pipeline.shader, d->pipeline.pair);
                    INFO(v.name << " " << ShaderVariantName(d->pipeline) << " in " << pass.name);
                    CHECK(int(kinds.size()) == BindingCount(d->pipeline));
                    std::set<int> bound;
                    for (const Binding& b : d->bindings) {
                        INFO("slot " << b.slot << ", plane " << PlaneName(b.plane.id));
                        REQUIRE(b.slot >= 0);
                        REQUIRE(size_t(b.slot) < kinds.size());
                        CHECK(bound.insert(b.slot).second);
                        CHECK(AccessFits(kinds[size_t(b.slot)], b.access));
                        CHECK((b.plane.side != HistorySide::None) == IsHistory(b.plane.id.kind));
                    }
                    CHECK(bound.size() == kinds.size());
                }
        });
    }
}

// The planes a composition's plan names are the ones its family and mechanism units declare
// (VariantPlanes): a unit cannot bring a plane it does not list, nor list one its passes leave out.
TEST_CASE("every composition's plan names exactly the planes its units declare") {
    size_t checked = 0;
    for (const std::string& name : DenoiserCompositions()) {
        const DenoiserVariant& v = FindDenoiserVariant(name);
        if (v.family == DenoiserFamily::Rae) continue;
        std::set<PlaneKind> named;
        for (const PlanePlacement& p : BuildDenoiserPlan(name, ParamsForVariant(v, DenoiserParams{}), 64, 64).planes)
            named.insert(p.key.id.kind);
        const std::vector<PlaneKind> declared = VariantPlanes(v);
        std::vector<std::string> missing, extra;
        for (PlaneKind kind : declared)
            if (!named.count(kind)) extra.push_back(PlaneName({kind, IsPerChannel(kind) ? Channel::Direct : Channel::None}));
        for (PlaneKind kind : named)
            if (std::find(declared.begin(), declared.end(), kind) == declared.end())
                missing.push_back(PlaneName({kind, IsPerChannel(kind) ? Channel::Direct : Channel::None}));
        INFO(name << ": declared but not in the plan: " << Catch::Detail::stringify(extra)
                  << "; in the plan but not declared: " << Catch::Detail::stringify(missing));
        CHECK(missing.empty());
        CHECK(extra.empty());
        ++checked;
    }
    CHECK(checked > 50);
}

TEST_CASE("each mechanism's own passes are in a composition's plan exactly where its flag is on, at its slot") {
    size_t checked = 0;
    for (const std::string& name : DenoiserCompositions()) {
        const DenoiserVariant& v = FindDenoiserVariant(name);
        if (v.family == DenoiserFamily::Rae) continue;
        ForEachPlanMode([&](const DenoiserParams& mode) {
            const DenoiserParams params = ParamsForVariant(v, mode);
            std::vector<std::string> order;
            for (const PlannedPass& pass : BuildDenoiserPlan(name, params, 64, 64).passes) order.push_back(pass.name);
            auto at = [&](std::string_view pass) {
                return size_t(std::find(order.begin(), order.end(), pass) - order.begin());
            };
            const plan::Family family(v, params, 64, 64);
            for (const MechanismFragment& m : MechanismFragments()) {
                std::vector<PlannedPass> own;
                plan::Writer w(own);
                plan::FrameCursor cursor;
                plan::FragmentOf(m.passes.pass)(w, family, cursor);
                REQUIRE(!own.empty());
                const size_t first = at(own.front().name);
                INFO(name << ": " << own.front().name << " in " << Catch::Detail::stringify(order));
                if (!(v.*m.flag)) {
                    for (const PlannedPass& pass : own) CHECK(at(pass.name) == order.size());
                    continue;
                }
                REQUIRE(first + own.size() <= order.size());
                for (size_t k = 0; k < own.size(); ++k) CHECK(order[first + k] == own[k].name);
                const size_t next = first + own.size();  // the pass after the fragment
                switch (m.passes.slot) {
                    case FrameSlot::BeforeGuide:
                        CHECK(first > at("upload"));
                        CHECK(order[next] == "pack_guide");
                        break;
                    case FrameSlot::AfterVariance:
                        CHECK(order[first - 1] == "filter_moments");
                        break;
                    case FrameSlot::BeforeBlend: CHECK(order[next] == "two_history_blend"); break;
                    case FrameSlot::AfterFilter:
                        CHECK(order[next] == "modulate");
                        CHECK(first > at("filter_moments"));
                        for (size_t k = next; k < order.size(); ++k) CHECK(order[k].rfind("atrous", 0) != 0);
                        break;
                }
            }
            ++checked;
        });
    }
    CHECK(checked > 50 * 12);
}
