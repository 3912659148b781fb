#include "denoise/pass_plan.h"

#include <fmt/format.h>

#include "core/frame_inputs.h"
#include "denoise/memory_plan.h"
#include "denoise/schedule.h"
#include "denoise/variants.h"

namespace fovrt {

namespace {

// Appends passes and the planes they use, in recording order.
class PlanWriter {
  public:
    explicit PlanWriter(std::vector<PlannedPass>& passes) : passes_(passes) {}

    PlanWriter& Pass(std::string name) {
        passes_.push_back({std::move(name), {}});
        return *this;
    }
    PlanWriter& Read(const std::string& plane, double times = 1.0,
                     Coverage coverage = Coverage::EveryPixel) {
        passes_.back().uses.push_back({plane, Access::Read, times, coverage});
        return *this;
    }
    PlanWriter& Write(const std::string& plane, double times = 1.0,
                      Coverage coverage = Coverage::EveryPixel) {
        passes_.back().uses.push_back({plane, Access::Write, times, coverage});
        return *this;
    }
    // Staging → device: the staging copy is read, the device plane written.
    PlanWriter& Upload(const std::string& plane, Coverage coverage = Coverage::EveryPixel) {
        return Write(plane, 2.0, coverage);
    }
    // A placeholder binding the shader loads on every pixel (its bytes are fixed, not a plane's).
    PlanWriter& ReadPlaceholder(const std::string& plane, double bytesPerPixel) {
        passes_.back().uses.push_back(
            {plane, Access::Read, 1.0, Coverage::EveryPixel, bytesPerPixel});
        return *this;
    }

  private:
    std::vector<PlannedPass>& passes_;
};

const char* const kGeometry[] = {"geometry.depth", "geometry.normal", "geometry.objectId"};

// The FrameInputs planes every SVGF-family frame uploads (DenoiserBuffers::RecordUploadInputs):
// the plane list but the sample counts, which only the variants that read them upload.
#define FOVRT_PLANE_NAME(member, Type, neutral, channels, doc) #member,
void UploadInputs(PlanWriter& w) {
    for (const char* plane : {FOVRT_FRAME_INPUT_PLANES(FOVRT_PLANE_NAME)})
        if (UploadedWithInputs(plane)) w.Upload(UploadBufferOf(plane));
}
#undef FOVRT_PLANE_NAME

// svgf_pack_guide: this frame's depth, normal, object id → the edge-stopping guide.
void PackGuide(PlanWriter& w) {
    w.Pass("pack_guide");
    for (const char* plane : kGeometry) w.Read(plane);
    w.Write("geometry.guide");
}

// What every reprojection shader reads once per pixel: both colour inputs, the geometry of this
// frame and the previous one, depth gradient and motion. The box-fallback pass over the listed
// pixels moves bytes only for those: none in the steady state.
void ReprojectionInputs(PlanWriter& w) {
    w.Read("input.direct").Read("input.indirect");
    for (const char* plane : kGeometry) w.Read(plane, 2.0);  // this frame and the previous one
    w.Read("input.depthGradient").Read("input.prevPixel");
}

// One history's share of "filter_moments": copy in → out for every pixel, and the 7×7 variance
// estimate of the listed pixels. `classify`: this history's channel is classified here (one list
// per channel serves both histories of two-history).
void FilterMoments(PlanWriter& w, const std::string& ch, const std::string& illum, bool classify) {
    const std::string in = ch + "." + illum + "0", out = ch + "." + illum + "1",
                      list = ch + ".spatialList";
    w.Read(in).Write(out);  // vkCmdCopyBuffer
    if (classify)
        w.Read("geometry.guide").Read(ch + ".length").Write(list, 1.0, Coverage::ListedPixels);
    const Coverage listed = Coverage::ListedPixels;
    w.Read(in, 1.0, listed)
        .Read("geometry.guide", 1.0, listed)
        .Read("input.depthGradient", 1.0, listed);
    w.Read(ch + ".moments", 1.0, listed).Read(ch + ".length", 1.0, listed).Read(list, 1.0, listed);
    w.Write(out, 1.0, listed);
}

// One à-trous history filtered at iteration i (0-based): illumination in → out, the colour
// history written on the feedback iteration.
void AtrousHistory(PlanWriter& w, const std::string& ch, const std::string& illum,
                   const std::string& history, int i, bool feedback) {
    w.Read(ch + "." + illum + ((i + 1) & 1 ? "1" : "0"))
        .Write(ch + "." + illum + (i & 1 ? "1" : "0"));
    if (feedback) w.Write(ch + "." + history);
}

// The guide and depth gradient of à-trous dispatches filtering `histories` illumination planes,
// up to two per dispatch (svgf_atrous_pair shares them).
void AtrousShared(PlanWriter& w, int histories) {
    const int dispatches = (histories + 1) / 2;
    w.Read("geometry.guide", dispatches).Read("input.depthGradient", dispatches);
}

// svgf_modulate: every channel's filtered illumination, the modulation factor, emission → output; then the
// output downloaded (device read + staging write).
void ModulateAndDownload(PlanWriter& w, const std::vector<std::string>& channels, int iterations) {
    w.Pass("modulate").Read("input.modulation").Read("input.emission");
    for (const std::string& ch : channels)
        w.Read(ch + ".illum" + std::to_string(FilteredIlluminationPlane(iterations)));
    w.Write("output");
    w.Pass("download").Read("output").Write("output");
}

void PlanSvgf(PlanWriter& w, const DenoiserVariant& v, const DenoiserParams& params) {
    const SvgfParams& p = params.svgf;
    const std::vector<std::string> channels = SvgfChannels(p);
    const bool weighted = p.weightBySampleCount;
    const int feedback = FeedbackIteration(p, false);
    w.Pass("upload");
    UploadInputs(w);
    if (v.needsSampleCount) w.Upload("input.sampleCount");
    PackGuide(w);
    // One dispatch for both channels (svgf_reproject_pair; combined: one channel of direct +
    // indirect).
    w.Pass("reproject");
    ReprojectionInputs(w);
    if (weighted) w.Read("input.sampleCount");
    for (const std::string& ch : channels) {
        // Previous frame's histories gathered, this frame's written; the colour history only
        // without à-trous feedback (else the feedback iteration writes it).
        w.Read(ch + ".color").Read(ch + ".moments").Read(ch + ".length");
        if (feedback == 0) w.Write(ch + ".color");
        w.Write(ch + ".moments").Write(ch + ".length");
        if (weighted) w.Read(ch + ".weight").Write(ch + ".weight");
        w.Write(ch + ".illum0");
    }
    w.Pass("filter_moments");
    for (const std::string& ch : channels) FilterMoments(w, ch, "illum", true);
    for (int i = 0; i < p.atrousIterations; ++i) {
        w.Pass(fmt::format("atrous{}", i));
        AtrousShared(w, int(channels.size()));
        for (const std::string& ch : channels)
            AtrousHistory(w, ch, "illum", "color", i, i + 1 == feedback);
    }
    ModulateAndDownload(w, channels, p.atrousIterations);
}

// A-SVGF's temporal gradient at stratum resolution: claim-slot fill, claim, gather (with the
// stratum guide), σ_l·std, à-trous iterations; then the per-pixel α and λ.
void PlanAsvgfGradient(PlanWriter& w, const DenoiserParams& params) {
    w.Pass("asvgf_gradient");
    w.Write("asvgf.claim");  // vkCmdFillBuffer: every slot empty
    // asvgf_gradient_claim: the uploaded samples, atomicMin on the claimed slots.
    w.Read("asvgf.samples", 1.0, Coverage::UploadedSamples)
        .Write("asvgf.claim", 2.0, Coverage::ClaimedStrata);
    // asvgf_gradient_gather: the claimed samples → (δ, Δ), and the stratum guide from the per-pixel
    // planes at the guide pixels.
    w.Read("asvgf.claim").Read("asvgf.samples", 0.5, Coverage::ClaimedStrata).Write("asvgf.grad0");
    for (const char* plane :
         {"geometry.objectId", "geometry.depth", "geometry.normal", "input.depthGradient",
          "input.direct", "input.indirect", "input.modulation", "input.emission"})
        w.Read(plane, 1.0, Coverage::StratumGuidePixels);
    w.Write("asvgf.guideGeometry").Write("asvgf.guideLuminance");
    // asvgf_stratum_sigma
    w.Read("asvgf.guideGeometry").Read("asvgf.guideLuminance").Write("asvgf.sigmaL");
    for (int i = 0; i < params.asvgf.gradientIterations; ++i) {
        w.Read(i & 1 ? "asvgf.grad1" : "asvgf.grad0").Write(i & 1 ? "asvgf.grad0" : "asvgf.grad1");
        w.Read("asvgf.guideGeometry").Read("asvgf.guideLuminance").Read("asvgf.sigmaL");
    }
    const int gi = params.asvgf.gradientIterations;
    w.Pass("asvgf_alpha").Read(gi > 0 && (gi - 1) % 2 == 0 ? "asvgf.grad1" : "asvgf.grad0");
    w.Write("asvgf.alpha").Write("asvgf.lambda");
}

void PlanTwoHistoryFamily(PlanWriter& w, const DenoiserVariant& v, const DenoiserParams& params) {
    const SvgfParams& p = params.svgf;
    const std::vector<std::string> channels = SvgfChannels(p);
    const bool two = v.twoHistory, ema = v.emaGradient;
    const int feedback = FeedbackIteration(p, two);
    w.Pass("upload");
    UploadInputs(w);
    if (v.needsSampleCount) w.Upload("input.sampleCount");
    if (v.asvgfGradient) w.Upload("asvgf.samples", Coverage::UploadedSamples);
    if (v.asvgfGradient) PlanAsvgfGradient(w, params);
    PackGuide(w);

    // two_history_reproject: one dispatch for both channels (pair; combined: one channel).
    w.Pass("two_history_reproject");
    ReprojectionInputs(w);
    if (two)
        w.Read("input.sampleCount");
    else  // the shader loads a sample count on every pixel; A-SVGF binds a placeholder
        w.ReadPlaceholder("input.prevPixel", 2.0);
    if (v.asvgfGradient) w.Read("asvgf.alpha");
    w.Read(channels[0] + ".length");  // W_u, gathered once
    if (two) w.Read("wweight").Write("wweight").Read("powerSums").Write("powerSums");
    if (ema) w.Read("gradient").Write("gradient");
    for (const std::string& ch : channels) {
        w.Read(ch + ".color").Read(ch + ".moments");  // previous I_u and moments, gathered
        w.Write(ch + ".moments").Write(ch + ".length").Write(ch + ".illum0");
        if (feedback == 0) w.Write(ch + ".color");
        if (two) {
            w.Read(ch + ".wcolor").Write(ch + ".willum0");
            if (feedback == 0) w.Write(ch + ".wcolor");
        }
    }

    w.Pass("filter_moments");
    for (const std::string& ch : channels) {
        FilterMoments(w, ch, "illum", true);
        if (two) FilterMoments(w, ch, "willum", false);  // one list per channel serves both
    }
    if (ema) {
        // 5×5 filter of g on the packed guide, each channel's variance → q.
        w.Pass("two_history_gradient")
            .Read("gradient")
            .Read("geometry.guide")
            .Read("input.depthGradient");
        for (const std::string& ch : channels) w.Read(ch + ".illum1");
        w.Write("q");
    }
    // two_history_blend per channel, in place on I_u: W_u (channel 0's length), W_w, S, and q
    // (λ̂ with A-SVGF). Runs after à-trous iteration 0, or after the variance estimate.
    auto blend = [&](const std::string& illum) {
        w.Pass("two_history_blend");
        for (const std::string& ch : channels) {
            w.Read(ch + ".illum" + illum).Write(ch + ".illum" + illum).Read(ch + ".willum" + illum);
            w.Read(channels[0] + ".length")
                .Read("wweight")
                .Read("powerSums")
                .Read(ema ? "q" : "asvgf.lambda");
        }
    };
    if (two && p.atrousIterations == 0) blend("1");
    for (int i = 0; i < p.atrousIterations; ++i) {
        const bool both = two && i == 0;  // iteration 0 filters I_u and I_w
        w.Pass(fmt::format("atrous{}", i));
        AtrousShared(w, int(channels.size()) * (both ? 2 : 1));
        for (const std::string& ch : channels) {
            AtrousHistory(w, ch, "illum", "color", i, i + 1 == feedback);
            if (both) AtrousHistory(w, ch, "willum", "wcolor", i, i + 1 == feedback);
        }
        if (both) blend("0");
    }
    ModulateAndDownload(w, channels, p.atrousIterations);
}

// The recurrent autoencoder (denoise/rae_weights.h): features on the host, the network's encoder
// (recurrent blocks: the previous hidden side read, the other written) and decoder (reading the
// hidden states as skips) on the device, remodulation on the host. Every activation counts once
// per pass that writes or reads it (the byte model's convention; a conv's 3×3 taps hit cache).
void PlanRae(PlanWriter& w, const std::vector<BufferPlan>& buffers) {
    auto unsided = [](const std::string& n) {
        const size_t dot = n.rfind('.');
        return n.rfind("rae.hidden", 0) == 0 ? n.substr(0, dot) : n;
    };
    auto starts = [](const std::string& n, const char* p) { return n.rfind(p, 0) == 0; };
    w.Pass("rae_features").Write("rae.input");
    w.Pass("upload").Upload("rae.input");
    w.Pass("rae_encoder").Read("rae.input").Read("rae.weights");
    for (const BufferPlan& b : buffers) {
        if (starts(b.name, "rae.enc") || starts(b.name, "rae.bottleneck")) w.Write(b.name).Read(b.name);
        if (starts(b.name, "rae.hidden") && b.name.back() == 'A') w.Read(unsided(b.name)).Write(unsided(b.name));
    }
    w.Pass("rae_decoder").Read("rae.weights").Write("rae.output");
    for (const BufferPlan& b : buffers) {
        if (starts(b.name, "rae.dec")) w.Write(b.name).Read(b.name);
        if (starts(b.name, "rae.hidden") && b.name.back() == 'A') w.Read(unsided(b.name));
    }
    w.Pass("download").Read("rae.output", 2.0);
    w.Pass("rae_remodulate").Read("rae.output");
}

}  // namespace

DenoiserPlan BuildDenoiserPlan(std::string_view name, const DenoiserParams& params, int width,
                               int height) {
    const DenoiserVariant& v = FindDenoiserVariant(name);
    const DenoiserParams p = ParamsForVariant(v, params);
    DenoiserPlan plan;
    plan.buffers = PlanDenoiserMemory(std::string(name), width, height, p);
    PlanWriter w(plan.passes);
    if (v.family == DenoiserFamily::Svgf)
        PlanSvgf(w, v, p);
    else if (v.family == DenoiserFamily::Rae)
        PlanRae(w, plan.buffers);
    else
        PlanTwoHistoryFamily(w, v, p);
    return plan;
}

}  // namespace fovrt
