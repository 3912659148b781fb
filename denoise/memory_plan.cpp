#include "denoise/rae_weights.h"
#include "denoise/memory_plan.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/error.h"
#include "core/frame_inputs.h"
#include "denoise/gradient_strata.h"
#include "denoise/variants.h"

namespace fovrt {

// uint16 sample counts, padded to whole 32-bit words (the shaders read packed pairs).
size_t SampleCountBytes(size_t pixels) { return ((sizeof(uint16_t) * pixels + 3) / 4) * 4; }

std::string UploadBufferOf(std::string_view plane, std::string_view side) {
    // The albedo plane's upload holds the frame's modulation factor (FrameInputs::Modulation():
    // albedo, or F_β under brdf demodulation), which the shaders remodulate by.
    std::string name = plane == "linearDepth"                        ? "geometry.depth"
                       : plane == "normal" || plane == "objectId" ? "geometry." + std::string(plane)
                       : plane == "albedo"                        ? "input.modulation"
                                                                  : "input." + std::string(plane);
    if (!side.empty() && name.rfind("geometry.", 0) == 0) name.append(".").append(side);
    return name;
}

std::vector<BufferPlan> PlanSvgfMemory(int width, int height, const DenoiserParams& params) {
    if (width <= 0 || height <= 0) Fail("memory plan: invalid size {}x{}", width, height);
    const size_t n = size_t(width) * size_t(height);
    const size_t hs = HistoryScalarBytes(params.precision);
    const bool weighted = params.svgf.weightBySampleCount;
    std::vector<BufferPlan> plan;
    auto add = [&](const std::string& name, size_t bytes, bool history) { plan.push_back({name, bytes, history}); };
    // Per-frame uploads from the FrameInputs plane list, in its order (the staging layout follows
    // it): input.<plane>, and this frame's geometry into A/B pairs (next frame's "previous").
    // Sample counts only for the variants that read them (uint16, padded to whole words).
    std::vector<BufferPlan> geometry;
    size_t uploadStaging = 0;
    auto upload = [&](std::string_view plane, size_t elementBytes) {
        const std::string name = UploadBufferOf(plane);
        if (!UploadedWithInputs(plane)) {  // the sample counts: svgf-weighted's own upload
            if (plane != "sampleCount" || !weighted) return;
            add(name, SampleCountBytes(n), false);
            uploadStaging += StagingAlign(SampleCountBytes(n));
            return;
        }
        uploadStaging += StagingAlign(elementBytes * n);
        if (name.rfind("geometry.", 0) == 0)
            geometry.push_back({name, elementBytes * n, true});
        else
            add(name, elementBytes * n, false);
    };
#define FOVRT_PLANE_UPLOAD(member, Type, neutral, channels, doc) upload(#member, sizeof(Type));
    FOVRT_FRAME_INPUT_PLANES(FOVRT_PLANE_UPLOAD)
#undef FOVRT_PLANE_UPLOAD
    for (const char* side : {"A", "B"})
        for (const BufferPlan& g : geometry) add(fmt::format("{}.{}", g.name, side), g.bytes, true);
    for (const std::string& ch : SvgfChannels(params.svgf)) {
        for (const char* side : {"A", "B"}) {
            add(fmt::format("{}.color.{}", ch, side), 3 * hs * n, true);
            add(fmt::format("{}.moments.{}", ch, side), 2 * hs * n, true);
            add(fmt::format("{}.length.{}", ch, side), hs * n, true);
            if (weighted) add(fmt::format("{}.weight.{}", ch, side), hs * n, true);
        }
        add(ch + ".illum0", 16 * n, false);
        add(ch + ".illum1", 16 * n, false);
        // Pixels needing the spatial variance estimate (Vulkan: svgf_moments_classify) + the
        // indirect dispatch arguments (groups x, y, z, count). Earlier in the frame the first
        // channel's list holds the reprojection's box-fallback pixels (svgf_reproject,
        // two_history_reproject): used up before the classify pass refills it, so no buffer of its own.
        add(ch + ".spatialList", 4 * n, false);
        add(ch + ".spatialArgs", 16, false);
    }
    // Edge-stopping guide of the Vulkan spatial filters (svgf_pack_guide: normal, depth; scratch).
    add("geometry.guide", 16 * n, false);
    add("output", 12 * n, false);
    add("stats", 8, false);
    // Staging: every upload, then output + stats.
    add("staging", uploadStaging + StagingAlign(12 * n) + StagingAlign(8), false);
    return plan;
}

std::vector<BufferPlan> PlanTwoHistoryExtraMemory(const std::string& name, int width, int height,
                                                  const DenoiserParams& params) {
    const DenoiserVariant& v = FindDenoiserVariant(name);
    if (v.family != DenoiserFamily::TwoHistory) return {};
    const size_t n = size_t(width) * size_t(height);
    const size_t hs = HistoryScalarBytes(params.precision);
    std::vector<BufferPlan> plan;
    auto add = [&](const std::string& what, size_t bytes, bool history) {
        plan.push_back({what, bytes, history});
    };
    const size_t sampleCountBytes = SampleCountBytes(n);
    const size_t sampleBytes = GradientSampleCapacity(width, height) * sizeof(GradientSample);
    if (v.twoHistory) {
        for (const std::string& ch : SvgfChannels(params.svgf)) {
            add(ch + ".wcolor.A", 3 * hs * n, true);
            add(ch + ".wcolor.B", 3 * hs * n, true);
            add(ch + ".willum0", 16 * n, false);
            add(ch + ".willum1", 16 * n, false);
        }
        for (const char* side : {"A", "B"}) {
            add(std::string("wweight.") + side, hs * n, true);
            add(std::string("powerSums.") + side, 3 * hs * n, true);
            // g as one float (its luminance); two-history-asvgf takes q from A-SVGF instead.
            if (v.emaGradient)
                add(std::string("gradient.") + side, hs * n, true);
        }
        // q of the EMA gradient (two-history-asvgf blends with A-SVGF's λ̂ instead).
        if (v.emaGradient) add("q", 4 * n, false);
    }
    if (v.needsSampleCount) add("input.sampleCount", sampleCountBytes, false);
    if (v.asvgfGradient) {
        const ivec2 g = StratumGridSize(width, height);
        const size_t strata = size_t(g.x) * size_t(g.y);
        add("asvgf.samples", sampleBytes, false);
        add("asvgf.claim", 4 * strata, false);
        add("asvgf.grad0", 8 * strata, false);
        add("asvgf.grad1", 8 * strata, false);
        // Stratum guide (Vulkan: asvgf_gradient_gather): normal + depth, luminance + depth
        // gradient, and σ_l·std (asvgf_stratum_sigma).
        add("asvgf.guideGeometry", 16 * strata, false);
        add("asvgf.guideLuminance", 16 * strata, false);
        add("asvgf.sigmaL", 4 * strata, false);
        add("asvgf.alpha", 4 * n, false);
        add("asvgf.lambda", 4 * n, false);
    }
    add("staging.extra", StagingAlign(sampleCountBytes) + StagingAlign(sampleBytes), false);
    return plan;
}

std::vector<BufferPlan> PlanTwoHistoryMemory(const std::string& name, int width, int height,
                                             const DenoiserParams& params) {
    std::vector<BufferPlan> plan = PlanSvgfMemory(width, height, params);
    for (BufferPlan& b : PlanTwoHistoryExtraMemory(name, width, height, params))
        plan.push_back(std::move(b));
    return plan;
}

std::vector<BufferPlan> PlanDenoiserMemory(const std::string& name, int width, int height,
                                           const DenoiserParams& params) {
    const DenoiserVariant& v = FindDenoiserVariant(name);
    const DenoiserParams p = ParamsForVariant(v, params);
    if (v.family == DenoiserFamily::Svgf) return PlanSvgfMemory(width, height, p);
    if (v.family == DenoiserFamily::Rae) return PlanRaeMemory(width, height, p);
    return PlanTwoHistoryMemory(name, width, height, p);
}

size_t TotalBytes(const std::vector<BufferPlan>& plan) {
    size_t total = 0;
    for (const auto& b : plan) total += b.bytes;
    return total;
}

size_t HistoryBytes(const std::vector<BufferPlan>& plan) {
    size_t total = 0;
    for (const auto& b : plan)
        if (b.history) total += b.bytes;
    return total;
}

void EnforceMemoryBudget(const std::vector<BufferPlan>& plan, size_t budgetBytes, const std::string& what) {
    if (budgetBytes == 0) return;
    size_t total = TotalBytes(plan);
    if (total <= budgetBytes) return;
    std::vector<BufferPlan> sorted = plan;
    std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.bytes > b.bytes; });
    std::string largest;
    for (size_t i = 0; i < std::min<size_t>(3, sorted.size()); ++i)
        largest += fmt::format("{}{} ({:.1f} MiB)", i ? ", " : "", sorted[i].name, sorted[i].bytes / 1048576.0);
    Fail("--memory-budget {} bytes exceeded: {} needs {} bytes ({:.1f} MiB); largest buffers: {}",
         budgetBytes, what, total, total / 1048576.0, largest);
}

std::string FormatMemoryPlan(const std::vector<BufferPlan>& plan, int width, int height) {
    const double pixels = double(width) * double(height);
    std::string out = fmt::format("{:<28} {:>14} {:>10} {}\n", "buffer", "bytes", "B/pixel", "kind");
    for (const auto& b : plan)
        out += fmt::format("{:<28} {:>14} {:>10.2f} {}\n", b.name, b.bytes, b.bytes / pixels,
                           b.history ? "history" : "scratch");
    size_t total = TotalBytes(plan), hist = HistoryBytes(plan);
    out += fmt::format("{:<28} {:>14} {:>10.2f}\n", "history total", hist, hist / pixels);
    out += fmt::format("{:<28} {:>14} {:>10.2f}\n", "total", total, total / pixels);
    return out;
}

}  // namespace fovrt
