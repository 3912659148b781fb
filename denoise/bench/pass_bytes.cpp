#include "denoise/bench/pass_bytes.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/error.h"
#include "denoise/gradient_strata.h"
#include "denoise/pass_plan.h"
#include "denoise/variants.h"

namespace fovrt {

namespace {

// The share of a plane a use of this coverage touches.
double CoverageShare(Coverage coverage, int width, int height, const PassBytesOptions& o) {
    switch (coverage) {
        case Coverage::EveryPixel: return 1.0;
        case Coverage::ListedPixels: return o.spatialFraction;
        case Coverage::FallbackPixels: return 0.0;  // the steady state: every pixel reprojects
        case Coverage::StratumGuidePixels: {
            const ivec2 grid = StratumGridSize(width, height);
            return double(grid.x) * double(grid.y) / (double(width) * double(height));
        }
        case Coverage::ClaimedStrata: return std::clamp(o.gradientSamplesPerStratum, 0.0, 1.0);
        case Coverage::UploadedSamples: return std::clamp(o.gradientSamplesPerStratum / 2.0, 0.0, 1.0);
    }
    return 1.0;
}

// Σ over every use of every pass of the plan: the byte model.
// The GPU passes by their timer names; with `reference`, the C++ reference's timers instead, each
// the sum of the passes it spans (a pass it runs no stage for keeps its own name).
std::vector<PassBytes> PlanPassBytes(const DenoiserPlan& plan, int width, int height, const PassBytesOptions& o,
                                     bool reference) {
    std::vector<PassBytes> out;
    for (const PlannedPass& pass : plan.passes) {
        if (pass.uses.empty() && pass.name.empty()) continue;  // untimed, not the steady state
        double bytes = 0.0;
        for (const PlaneUse& use : pass.uses)
            bytes += use.times * CoverageShare(use.coverage, width, height, o) *
                     (use.fixedBytesPerPixel > 0.0 ? use.fixedBytesPerPixel : use.planeBytesPerPixel);
        const std::string& name = reference && !pass.referenceTimer.empty() ? pass.referenceTimer : pass.name;
        auto same = std::find_if(out.begin(), out.end(), [&](const PassBytes& b) { return b.pass == name; });
        if (same != out.end()) same->bytesPerPixel += bytes;
        else out.push_back({name, bytes});
    }
    return out;
}

}  // namespace

std::vector<PassBytes> SvgfPassBytes(int width, int height, const DenoiserParams& params, const PassBytesOptions& o) {
    const char* name = params.svgf.weightBySampleCount ? "svgf-weighted" : "svgf";
    return PlanPassBytes(BuildDenoiserPlan(name, params, width, height), width, height, o, false);
}

std::vector<PassBytes> DenoiserPassBytes(const std::string& name, const std::string& backend, int width, int height,
                                         const DenoiserParams& params, const PassBytesOptions& o) {
    if (!LookupDenoiserVariant(name)) Fail("pass bytes: unknown denoiser '{}'", name);
    if (backend != "vulkan" && backend != "cpu") Fail("pass bytes: unknown backend '{}'", backend);
    return PlanPassBytes(BuildDenoiserPlan(name, params, width, height), width, height, o, backend == "cpu");
}

double CompulsoryBytesPerPixel(const DenoiserPlan& plan, int width, int height) {
    double bytes = 0.0;
    auto add = [&](const std::string& name, size_t size, bool history) {
        if (history || name.rfind("input.", 0) == 0 || name == "output") bytes += double(size);
    };
    for (const PlanePlacement& p : plan.planes) add(BufferName(p.key), p.bytes, IsHistory(p.key.id.kind));
    if (plan.planes.empty())  // the RAE: its buffers are its planes
        for (const BufferPlan& b : plan.buffers) add(b.name, b.bytes, b.history);
    return bytes / (double(width) * double(height));
}

}  // namespace fovrt
