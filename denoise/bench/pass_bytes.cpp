#include "denoise/bench/pass_bytes.h"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "core/error.h"
#include "denoise/reference/asvgf_ref.h"
#include "denoise/denoiser_factory.h"
#include "denoise/memory_plan.h"
#include "denoise/schedule.h"
#include "denoise/reference/two_history_ref.h"

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
    bool Has(const std::string& name) const { return bytes_.count(name) || bytes_.count(name + ".A"); }

private:
    double pixels_;
    std::map<std::string, double> bytes_;
};

// The per-frame uploads RecordUploadInputs records (staging → device: read + write each).
double UploadBytes(const PlanBytes& b) {
    double up = 0.0;
    for (const char* name : {"input.direct", "input.indirect", "input.albedo", "input.emission", "input.depthGradient",
                             "input.prevPixel", "geometry.depth", "geometry.normal", "geometry.objectId"})
        up += b(name);
    return up;
}

double GeometryBytes(const PlanBytes& b) { return b("geometry.depth") + b("geometry.normal") + b("geometry.objectId"); }

// svgf_pack_guide: this frame's depth, normal, object id → guide.
double PackGuideBytes(const PlanBytes& b) { return GeometryBytes(b) + b("geometry.guide"); }

// filter_moments as recorded, per history filtered: classify (guide, length → list of the pixels
// below the threshold), copy illum0 → illum1, then svgf_filter_moments on the listed pixels only
// (illumination, guide, depth gradient, moments, length, list → illum1).
double FilterMomentsBytes(const PlanBytes& b, const std::string& ch, const std::string& illum, bool classify,
                          double spatial) {
    const double list = b(ch + ".spatialList");
    double bytes = 2 * b(ch + "." + illum + "0");  // vkCmdCopyBuffer: read + write
    if (classify) bytes += b("geometry.guide") + b(ch + ".length") + spatial * list;
    bytes += spatial * (b(ch + "." + illum + "0") + b("geometry.guide") + b("input.depthGradient") +
                        b(ch + ".moments") + b(ch + ".length") + list + b(ch + "." + illum + "1"));
    return bytes;
}

// One history's share of an à-trous iteration: illumination in/out, the colour history when this
// iteration feeds back. The guide and depth gradient: AtrousSharedBytes, once per dispatch.
double AtrousChannelBytes(const PlanBytes& b, const std::string& ch, const std::string& illum,
                          const std::string& history, bool feedback) {
    return 2 * b(ch + "." + illum + "0") + (feedback ? b(ch + "." + history) : 0.0);
}

// Guide and depth gradient of the dispatches that filter `histories` illumination planes, up to
// kAtrousChannelsPerDispatch per dispatch (svgf_atrous_pair: they are fetched once for the pair).
double AtrousSharedBytes(const PlanBytes& b, int histories) {
    const int dispatches = (histories + kAtrousChannelsPerDispatch - 1) / kAtrousChannelsPerDispatch;
    return dispatches * (b("geometry.guide") + b("input.depthGradient"));
}

// svgf_modulate: every channel's filtered illumination, albedo, emission → output.
double ModulateBytes(const PlanBytes& b, const std::vector<std::string>& channels) {
    double bytes = b("input.albedo") + b("input.emission") + b("output");
    for (const std::string& ch : channels) bytes += b(ch + ".illum0");
    return bytes;
}

// Output + counters: device → staging (read + write).
double DownloadBytes(const PlanBytes& b) { return 2 * b("output"); }

DenoiserParams TwoHistoryFamilyParams(const DenoiserParams& params) {
    DenoiserParams p = params;
    p.svgf.weightBySampleCount = false;  // as TwoHistoryVulkanDenoiser
    return p;
}

}  // namespace

std::vector<PassBytes> SvgfPassBytes(int width, int height, const DenoiserParams& params,
                                     const PassBytesOptions& o) {
    const PlanBytes b(PlanSvgfMemory(width, height, params), width, height);
    const SvgfParams& p = params.svgf;
    const std::vector<std::string> channels = SvgfChannels(p);
    const bool weighted = p.weightBySampleCount;
    const int iterations = p.atrousIterations;
    const int feedback = FeedbackIteration(p, false);
    const bool atrousFeedback = feedback > 0;
    std::vector<PassBytes> out;
    out.push_back({"upload", 2 * (UploadBytes(b) + (weighted ? b("input.sampleCount") : 0.0))});
    out.push_back({"pack_guide", PackGuideBytes(b)});
    // One dispatch for both channels (svgf_reproject_pair; combined: one channel, colour = direct +
    // indirect): geometry of both frames, depth gradient, previous pixel and sample counts once;
    // per channel colour in, previous colour/moments/length/weight, this frame's moments, length,
    // weight, colour (no feedback), illumination. The box-fallback pass over the listed pixels
    // (shaders/common/reprojection.glsl) moves bytes only for those: none in the steady state.
    double reproject = b("input.direct") + b("input.indirect") + 2 * GeometryBytes(b) + b("input.depthGradient") +
                       b("input.prevPixel") + (weighted ? b("input.sampleCount") : 0.0);
    for (const std::string& ch : channels) {
        double history = b(ch + ".color") + b(ch + ".moments") + b(ch + ".length") + (weighted ? b(ch + ".weight") : 0);
        reproject += history + history - (atrousFeedback ? b(ch + ".color") : 0.0) + b(ch + ".illum0");
    }
    out.push_back({"reproject", reproject});
    double moments = 0.0;
    for (const std::string& ch : channels) moments += FilterMomentsBytes(b, ch, "illum", true, o.spatialFraction);
    out.push_back({"filter_moments", moments});
    for (int i = 0; i < iterations; ++i) {
        double atrous = AtrousSharedBytes(b, int(channels.size()));
        for (const std::string& ch : channels)
            atrous += AtrousChannelBytes(b, ch, "illum", "color", i + 1 == feedback);
        out.push_back({fmt::format("atrous{}", i), atrous});
    }
    out.push_back({"modulate", ModulateBytes(b, channels)});
    out.push_back({"download", DownloadBytes(b)});
    return out;
}

std::vector<PassBytes> AsvgfPassBytes(const std::string& name, int width, int height, const DenoiserParams& params,
                                      const PassBytesOptions& o) {
    const PlanBytes b(PlanTwoHistoryMemory(name, width, height, TwoHistoryFamilyParams(params)), width, height);
    if (!b.Has("asvgf.grad0")) Fail("pass bytes: '{}' has no A-SVGF gradient passes", name);
    // Stratum planes are whole-plane reads (b(...) already divides by the pixel count). Samples:
    // the plan holds the capacity, two per stratum.
    const double samplesRead = b("asvgf.samples") * std::clamp(o.gradientSamplesPerStratum / 2.0, 0.0, 1.0);
    const double claimed = std::clamp(o.gradientSamplesPerStratum, 0.0, 1.0);  // strata with a sample
    const ivec2 grid = StratumGridSize(width, height);
    const double strataPerPixel = double(grid.x) * double(grid.y) / (double(width) * double(height));
    double gradient = b("asvgf.claim");  // vkCmdFillBuffer: every slot empty
    if (samplesRead > 0) gradient += samplesRead + 2 * b("asvgf.claim") * claimed;  // claim: atomicMin
    // gather: claim slots, the claimed samples → (δ, Δ), and the stratum guide from the per-pixel
    // planes at the guide pixels (object id, depth, normal, depth gradient, the noisy colour's
    // direct, indirect, albedo, emission): one element per stratum.
    const double atGuide = (b("geometry.objectId") + b("geometry.depth") + b("geometry.normal") +
                            b("input.depthGradient") + b("input.direct") + b("input.indirect") + b("input.albedo") +
                            b("input.emission")) *
                           strataPerPixel;
    const double guide = b("asvgf.guideGeometry") + b("asvgf.guideLuminance");
    gradient += b("asvgf.claim") + b("asvgf.samples") / 2 * claimed + b("asvgf.grad0") + atGuide + guide;
    gradient += guide + b("asvgf.sigmaL");  // asvgf_stratum_sigma
    // Each à-trous iteration: (δ, Δ) in/out, the stratum guide and σ_l·std.
    gradient += params.asvgf.gradientIterations * (2 * b("asvgf.grad0") + guide + b("asvgf.sigmaL"));
    return {{"asvgf_gradient", gradient}, {"asvgf_alpha", b("asvgf.grad0") + b("asvgf.alpha") + b("asvgf.lambda")}};
}

std::vector<PassBytes> TwoHistoryPassBytes(const std::string& name, int width, int height,
                                           const DenoiserParams& params, const PassBytesOptions& o) {
    TwoHistoryVariant variant;
    if (!TwoHistoryVariantOf(name, variant)) Fail("pass bytes: '{}' is not a two-history/A-SVGF denoiser", name);
    const DenoiserParams dp = TwoHistoryFamilyParams(params);
    const SvgfParams& p = dp.svgf;
    const PlanBytes b(PlanTwoHistoryMemory(name, width, height, dp), width, height);
    const bool two = variant != TwoHistoryVariant::Asvgf;
    const bool asvgf = variant != TwoHistoryVariant::TwoHistory;
    const std::vector<std::string> channels = SvgfChannels(p);
    const int iterations = p.atrousIterations;
    const int feedback = FeedbackIteration(p, two);
    const double samples = asvgf ? b("asvgf.samples") * std::clamp(o.gradientSamplesPerStratum / 2.0, 0.0, 1.0) : 0.0;
    std::vector<PassBytes> out;
    out.push_back({"upload", 2 * (UploadBytes(b) + (two ? b("input.sampleCount") : 0.0) + samples)});
    if (asvgf)
        for (PassBytes& pb : AsvgfPassBytes(name, width, height, dp, o)) out.push_back(pb);
    out.push_back({"pack_guide", PackGuideBytes(b)});

    // two_history_reproject: one dispatch for both channels (two_history_reproject_pair; combined:
    // one channel, colour = direct + indirect). Once per pixel: both colours, geometry of both
    // frames, depth gradient, previous pixel, sample count, α, W_u gathered (channel 0's length),
    // W_w and S gathered and written, g gathered and written. The box-fallback pass: as SVGF's.
    double reproject = b("input.direct") + b("input.indirect") + 2 * GeometryBytes(b) + b("input.depthGradient") +
                       b("input.prevPixel");
    // The sample count is loaded unconditionally (asvgf binds a dummy plane: 2 bytes a pixel).
    reproject += two ? b("input.sampleCount") : 2.0;
    if (asvgf) reproject += b("asvgf.alpha");
    reproject += b(channels[0] + ".length");
    if (two) {
        reproject += 2 * (b("wweight") + b("powerSums"));
        // The EMA gradient (two-history only; two-history-asvgf takes A-SVGF's λ̂).
        if (variant == TwoHistoryVariant::TwoHistory) reproject += 2 * b("gradient");
    }
    // Per channel: previous I_u and moments (gathered), this frame's moments, W_u, (I_u, Var),
    // I_u (no feedback); two-history: previous I_w, (I_w, Var), I_w (no feedback).
    for (const std::string& ch : channels) {
        reproject += b(ch + ".color") + b(ch + ".moments");
        reproject += b(ch + ".moments") + b(ch + ".length") + b(ch + ".illum0") + (feedback == 0 ? b(ch + ".color") : 0.0);
        if (two) reproject += b(ch + ".wcolor") + b(ch + ".willum0") + (feedback == 0 ? b(ch + ".wcolor") : 0.0);
    }
    out.push_back({"two_history_reproject", reproject});

    double moments = 0.0;
    for (const std::string& ch : channels) {
        moments += FilterMomentsBytes(b, ch, "illum", true, o.spatialFraction);
        if (two) moments += FilterMomentsBytes(b, ch, "willum", false, o.spatialFraction);  // one list serves both
    }
    out.push_back({"filter_moments", moments});

    if (variant == TwoHistoryVariant::TwoHistory) {
        // 5×5 filter of g (this frame) on the packed guide, the variance of each channel's I_u → q.
        double gradient = b("gradient") + b("geometry.guide") + b("input.depthGradient") + b("q");
        for (const std::string& ch : channels) gradient += b(ch + ".illum1");
        out.push_back({"two_history_gradient", gradient});
    }

    // two_history_blend, per channel: (I_u, Var) read + written in place, (I_w, Var), W_u (channel
    // 0's length), W_w, S, q (λ̂ with A-SVGF).
    double blend = 0.0;
    if (two)
        for (const std::string& ch : channels)
            blend += 2 * b(ch + ".illum0") + b(ch + ".willum0") + b(channels[0] + ".length") + b("wweight") +
                     b("powerSums") + b(variant == TwoHistoryVariant::TwoHistory ? "q" : "asvgf.lambda");
    if (two && iterations == 0) out.push_back({"two_history_blend", blend});
    for (int i = 0; i < iterations; ++i) {
        double atrous = AtrousSharedBytes(b, int(channels.size()) * (two && i == 0 ? 2 : 1));
        for (const std::string& ch : channels) {
            atrous += AtrousChannelBytes(b, ch, "illum", "color", i + 1 == feedback);
            if (two && i == 0) atrous += AtrousChannelBytes(b, ch, "willum", "wcolor", i + 1 == feedback);
        }
        out.push_back({fmt::format("atrous{}", i), atrous});
        if (two && i == 0) out.push_back({"two_history_blend", blend});
    }
    out.push_back({"modulate", ModulateBytes(b, channels)});
    out.push_back({"download", DownloadBytes(b)});
    return out;
}

std::vector<PassBytes> DenoiserPassBytes(const std::string& name, const std::string& backend, int width, int height,
                                         const DenoiserParams& params, const PassBytesOptions& o) {
    const DenoiserParams p = ParamsForDenoiser(name, params);
    TwoHistoryVariant variant;
    const bool twoFamily = TwoHistoryVariantOf(name, variant);
    if (!twoFamily && name != "svgf" && name != "svgf-weighted") Fail("pass bytes: unknown denoiser '{}'", name);
    std::vector<PassBytes> vk = twoFamily ? TwoHistoryPassBytes(name, width, height, p, o)
                                          : SvgfPassBytes(width, height, p, o);
    if (backend == "vulkan" || !twoFamily) return vk;
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
