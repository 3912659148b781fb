// Byte models of the denoiser passes (denoise/bench/pass_bytes.h): every pass a denoiser actually times
// (names taken from real 64×64 runs, Vulkan and C++ reference, both precisions) has a model entry
// and nothing else does; the models hold at least the compulsory traffic of the memory plan; and
// spot values that follow from the shaders' bindings.
#include <algorithm>
#include <set>

#include "core/error.h"
#include "denoise/denoiser_factory.h"
#include "denoise/memory_plan.h"
#include "denoise/bench/pass_bytes.h"
#include "denoise_svgf_scenes.h"
#include "test_support.h"
#include "vk/context.h"
#include "vk_test_support.h"

using namespace fovrt;

namespace {

std::set<std::string> TimedPasses(const std::string& name, const std::string& backend, const DenoiserParams& params) {
    auto d = CreateDenoiser(name, backend, params, backend == "vulkan" ? test::TestContext().get() : nullptr);
    REQUIRE(d->Backend() == backend);
    Plane<vec3> out;
    std::set<std::string> passes;
    for (uint32_t t = 0; t < 3; ++t) {  // from the second frame on, every pass runs
        d->Denoise(test::RandomFrame(64, 64, 7, t), out);
        if (t == 0) continue;
        for (const PassTiming& p : d->LastTimings()) passes.insert(p.pass);
    }
    return passes;
}

std::set<std::string> ModelPasses(const std::vector<PassBytes>& model) {
    std::set<std::string> names;
    for (const PassBytes& p : model) names.insert(p.pass);
    return names;
}

}  // namespace

TEST_CASE("every timed pass of every denoiser has a byte model", "[bench]") {
    std::vector<std::string> backends = {"cpu"};
    if (VulkanContext::Available()) backends.push_back("vulkan");
    for (const std::string& backend : backends)
        for (Precision precision : {Precision::Fp32, Precision::Fp16})
            for (const std::string& name : DenoiserNames()) {
                if (backend == "vulkan" && precision == Precision::Fp16 && !test::TestContext()->supports16BitStorage())
                    continue;
                DenoiserParams params;
                params.precision = precision;
                const std::set<std::string> timed = TimedPasses(name, backend, params);
                const std::vector<PassBytes> model = DenoiserPassBytes(name, backend, 64, 64, params);
                INFO(name << " " << backend << (precision == Precision::Fp16 ? " fp16" : " fp32"));
                CHECK(timed.size() >= 4);
                for (const PassBytes& p : model) {
                    INFO(p.pass);
                    CHECK(p.bytesPerPixel > 0.0);
                    if (backend == "vulkan") CHECK(timed.count(p.pass) == 1);  // no model of a pass that never runs
                }
                const std::set<std::string> modelled = ModelPasses(model);
                for (const std::string& pass : timed) {
                    INFO(pass);
                    CHECK(modelled.count(pass) == 1);
                }
            }
    if (VulkanContext::Available()) CHECK(test::TestContext()->validationErrors() == 0);
}

TEST_CASE("pass byte models cover the compulsory traffic of the memory plan", "[bench]") {
    for (Precision precision : {Precision::Fp32, Precision::Fp16})
        for (bool combined : {false, true})
            for (const std::string& name : DenoiserNames())
                for (const char* backend : {"vulkan", "cpu"}) {
                    DenoiserParams params;
                    params.precision = precision;
                    params.svgf.filterCombined = combined;
                    double compute = 0.0;
                    for (const PassBytes& p : DenoiserPassBytes(name, backend, 96, 64, params))
                        if (p.pass != "upload" && p.pass != "download") compute += p.bytesPerPixel;
                    const double compulsory =
                        CompulsoryBytesPerPixel(BuildDenoiserPlan(name, params, 96, 64), 96, 64);
                    INFO(name << " " << backend << " combined " << combined);
                    CHECK(compulsory > 40.0);  // the least: the RAE's fp16 activations, 48 B/pixel
                    CHECK(compute >= compulsory);
                    CHECK(compute < 40 * compulsory);  // sanity: not counting every gather tap
                }
}

TEST_CASE("compulsory traffic counts every plane whether or not it shares a transient slot", "[bench]") {
    // svgf, fp32, direct and indirect apart: histories 2 × (geometry 20 + 2 channels × (colour 12 +
    // moments 8 + length 4)), the inputs the pool holds (4 × 12 + 2 × 8), the output 12.
    CHECK(CompulsoryBytesPerPixel(BuildDenoiserPlan("svgf", DenoiserParams{}, 96, 64), 96, 64) ==
          Approx(2 * (20 + 2 * 24) + 4 * 12 + 2 * 8 + 12));
}

TEST_CASE("SVGF pass bytes follow the shaders' bindings", "[bench]") {
    DenoiserParams p;  // two channels, fp32, 5 iterations, feedback after iteration 1
    const auto passes = SvgfPassBytes(64, 64, p);
    REQUIRE(passes.size() == 1 + 1 + 1 + 1 + 5 + 1 + 1);
    CHECK(passes[1].pass == "pack_guide");
    CHECK(passes[1].bytesPerPixel == Approx(4 + 12 + 4 + 16));
    CHECK(passes[2].pass == "reproject");
    // One à-trous iteration, both channels in one dispatch: per channel illumination in/out 32 B,
    // once guide 16 B + depth gradient 8 B; iteration 0 also writes the fp32 colour histories (12 B).
    CHECK(passes[4].bytesPerPixel == Approx(2 * (32 + 12) + 16 + 8));
    CHECK(passes[5].bytesPerPixel == Approx(2 * 32 + 16 + 8));
    // Reprojection, both channels in one dispatch: colour in 2·12, geometry of both frames 2·20,
    // depth gradient 8, motion 8 once; per channel fp32 history read 24 + written 12 (the colour
    // history is the à-trous feedback's), illumination 16.
    CHECK(passes[2].bytesPerPixel == Approx(24 + 40 + 8 + 8 + 2 * (24 + 12 + 16)));
    // Steady state filter_moments: classify (guide 16 + length 4) + copy illum0 → illum1 (32).
    CHECK(passes[3].bytesPerPixel == Approx(2 * (16 + 4 + 32)));
    PassBytesOptions all;
    all.spatialFraction = 1.0;
    CHECK(SvgfPassBytes(64, 64, p, all)[3].bytesPerPixel > passes[3].bytesPerPixel + 2 * 60);
    p.precision = Precision::Fp16;
    CHECK(SvgfPassBytes(64, 64, p)[2].bytesPerPixel < passes[2].bytesPerPixel);
    CHECK(SvgfPassBytes(64, 64, p)[5].bytesPerPixel == Approx(2 * 16 + 16 + 8));  // fp16 illumination in/out 8 + 8
    p.svgf.filterCombined = true;
    CHECK(SvgfPassBytes(64, 64, p)[5].bytesPerPixel == Approx(16 + 16 + 8));
}

TEST_CASE("two-history pass bytes follow the shaders' bindings", "[bench]") {
    DenoiserParams p;
    const auto model = DenoiserPassBytes("two-history", "vulkan", 64, 64, p);
    auto at = [&](const std::vector<PassBytes>& m, const std::string& pass) {
        for (const PassBytes& b : m)
            if (b.pass == pass) return b.bytesPerPixel;
        FAIL("no pass " << pass);
        return 0.0;
    };
    // Blend per channel: (I_u, Var) read + written 32, (I_w, Var) 16, W_u 4, W_w 4, S 12, q 4.
    CHECK(at(model, "two_history_blend") == Approx(2 * (32 + 16 + 4 + 4 + 12 + 4)));
    // The gradient filter: g (element size from the plan), guide 16, depth gradient 8, each
    // channel's (I_u, Var) 16, q 4.
    double g = 0.0;
    for (const BufferPlan& b : PlanDenoiserMemory("two-history", 64, 64, p))
        if (b.name == "gradient.A") g = double(b.bytes) / (64 * 64);
    CHECK(g > 0.0);
    CHECK(at(model, "two_history_gradient") == Approx(g + 16 + 8 + 2 * 16 + 4));
    // Reprojection, one dispatch for both channels: direct + indirect 24, geometry of both frames
    // 40, depth gradient 8, previous pixel 8, sample count 2, W_u gathered and written once 2·4
    // (the channels share it), W_w and S gathered and written 2·16, g gathered and written; per
    // channel previous I_u 12 and moments 8, this frame's moments 8, (I_u, Var) 16, previous I_w
    // 12, (I_w, Var) 16 (feedback 1: no colour writes).
    CHECK(at(model, "two_history_reproject") ==
          Approx(24 + 40 + 8 + 8 + 2 + 2 * 4 + 2 * 16 + 2 * g + 2 * (12 + 8 + 8 + 16 + 12 + 16)));
    // Iteration 0 filters both histories of both channels (two pair dispatches: guide and depth
    // gradient read twice) and writes all four colour histories.
    CHECK(at(model, "atrous0") == Approx(2 * 2 * (32 + 12) + 2 * (16 + 8)));
    CHECK(at(model, "atrous1") == Approx(2 * 32 + 16 + 8));
    // The reference's atrous_blend is the sum of the Vulkan passes it spans.
    const auto ref = DenoiserPassBytes("two-history", "cpu", 64, 64, p);
    double sum = at(model, "two_history_blend");
    for (int i = 0; i < p.svgf.atrousIterations; ++i) sum += at(model, "atrous" + std::to_string(i));
    CHECK(at(ref, "atrous_blend") == Approx(sum));
    const auto asvgf = DenoiserPassBytes("asvgf", "vulkan", 64, 64, p);
    const auto asvgfRef = DenoiserPassBytes("asvgf", "cpu", 64, 64, p);
    CHECK(at(asvgfRef, "asvgf_gradient") == Approx(at(asvgf, "asvgf_gradient") + at(asvgf, "asvgf_alpha")));
    // α and λ per pixel (8 B) + the stratum gradient (8 B per 3×3 stratum).
    CHECK(at(asvgf, "asvgf_alpha") == Approx(8 + 8.0 * 22 * 22 / (64 * 64)));
    // A-SVGF's reprojection: no weighted history, no g; α 4, a dummy sample count 2, and W_u
    // gathered and written once for both channels 2·4.
    // Its timer is "reproject": one history, as SVGF's, though through the two-history shader.
    CHECK(std::none_of(asvgf.begin(), asvgf.end(), [](const PassBytes& b) { return b.pass == "two_history_reproject"; }));
    CHECK(at(asvgf, "reproject") == Approx(24 + 40 + 8 + 8 + 2 + 4 + 2 * 4 + 2 * (12 + 8 + 8 + 16)));
    CHECK_THROWS_AS(DenoiserPassBytes("nope", "vulkan", 64, 64, p), Error);
}
