#include "denoise/bench/pass_bytes.h"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "core/error.h"
#include "denoise/gradient_strata.h"
#include "denoise/memory_plan.h"
#include "denoise/pass_plan.h"
#include "denoise/variants.h"

namespace fovrt {

namespace {

// Bytes per image pixel of one whole buffer of the plan (A/B histories: one side). Per-pixel
// planes give their element size; stratum planes their size / 9; fixed-size buffers ~0.
class PlanBytes {
public:
    PlanBytes(const std::vector<BufferPlan>& plan, int width, int height)
        : pixels_(double(width) * double(height)) {
        if (width <= 0 || height <= 0) Fail("pass bytes: invalid size {}x{}", width, height);
        for (const BufferPlan& b : plan) bytes_[b.name] = double(b.bytes);
    }
    double operator()(const std::string& name) const {
        auto it = bytes_.find(name);
        if (it == bytes_.end()) it = bytes_.find(name + ".A");
        if (it == bytes_.end()) Fail("pass bytes: no buffer '{}' in the memory plan", name);
        return it->second / pixels_;
    }

private:
    double pixels_;
    std::map<std::string, double> bytes_;
};

// The share of a plane a use of this coverage touches.
double CoverageShare(Coverage coverage, int width, int height, const PassBytesOptions& o) {
    switch (coverage) {
        case Coverage::EveryPixel: return 1.0;
        case Coverage::ListedPixels: return o.spatialFraction;
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
std::vector<PassBytes> PlanPassBytes(const DenoiserPlan& plan, int width, int height, const PassBytesOptions& o) {
    const PlanBytes b(plan.buffers, width, height);
    std::vector<PassBytes> out;
    for (const PlannedPass& pass : plan.passes) {
        double bytes = 0.0;
        for (const PlaneUse& use : pass.uses)
            bytes += use.times * CoverageShare(use.coverage, width, height, o) *
                     (use.fixedBytesPerPixel > 0.0 ? use.fixedBytesPerPixel : b(use.plane));
        out.push_back({pass.name, bytes});
    }
    return out;
}

}  // namespace

std::vector<PassBytes> SvgfPassBytes(int width, int height, const DenoiserParams& params, const PassBytesOptions& o) {
    const char* name = params.svgf.weightBySampleCount ? "svgf-weighted" : "svgf";
    return PlanPassBytes(BuildDenoiserPlan(name, params, width, height), width, height, o);
}

std::vector<PassBytes> DenoiserPassBytes(const std::string& name, const std::string& backend, int width, int height,
                                         const DenoiserParams& params, const PassBytesOptions& o) {
    const DenoiserVariant* variant = LookupDenoiserVariant(name);
    if (!variant) Fail("pass bytes: unknown denoiser '{}'", name);
    const std::vector<PassBytes> vk = PlanPassBytes(BuildDenoiserPlan(name, params, width, height), width, height, o);
    if (backend == "vulkan" || variant->family != DenoiserFamily::TwoHistory) return vk;
    if (backend != "cpu") Fail("pass bytes: unknown backend '{}'", backend);
    // The reference's passes: the same names, except two that span several Vulkan passes.
    std::vector<PassBytes> ref;
    auto sum = [&](auto pred) {
        double s = 0.0;
        for (const PassBytes& pb : vk)
            if (pred(pb.pass)) s += pb.bytesPerPixel;
        return s;
    };
    for (const PassBytes& pb : vk) {
        if (pb.pass == "asvgf_gradient")
            ref.push_back({"asvgf_gradient", sum([](const std::string& s) { return s.rfind("asvgf_", 0) == 0; })});
        else if (pb.pass == "two_history_reproject" || pb.pass == "filter_moments" ||
                 pb.pass == "two_history_gradient" || pb.pass == "modulate")
            ref.push_back(pb);
    }
    const double atrousBlend = sum([](const std::string& s) { return s.rfind("atrous", 0) == 0 || s == "two_history_blend"; });
    auto at = std::find_if(ref.begin(), ref.end(), [](const PassBytes& pb) { return pb.pass == "modulate"; });
    ref.insert(at, {"atrous_blend", atrousBlend});
    return ref;
}

double CompulsoryBytesPerPixel(const std::vector<BufferPlan>& plan, int width, int height) {
    double bytes = 0.0;
    for (const BufferPlan& b : plan)
        if (b.history || b.name.rfind("input.", 0) == 0 || b.name == "output") bytes += double(b.bytes);
    return bytes / (double(width) * double(height));
}

}  // namespace fovrt
