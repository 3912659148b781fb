#include "denoise/svgf_family_plan.h"

#include <fmt/format.h>

#include <utility>

#include "denoise/gradient_strata.h"
#include "denoise/schedule.h"
#include "shaders/push_constants.h"

namespace fovrt {

namespace {

PlaneRef Shared(PlaneKind kind) { return {{kind, Channel::None}, HistorySide::None}; }
PlaneRef Scratch(PlaneKind kind, Channel ch) { return {{kind, ch}, HistorySide::None}; }
PlaneRef This(PlaneKind kind, Channel ch = Channel::None) { return {{kind, ch}, HistorySide::This}; }
PlaneRef Previous(PlaneKind kind, Channel ch = Channel::None) {
    return {{kind, ch}, HistorySide::Previous};
}
// Bound where a mode leaves a slot unread / unwritten: planes every plan has.
const PlaneRef kUnreadSlot = Shared(PlaneKind::PrevPixel);
const PlaneRef kUnwrittenSlot = Shared(PlaneKind::Output);

// A dispatch's bindings, slot by slot.
class Bindings {
  public:
    Bindings& Read(int slot, PlaneRef p, Coverage c = Coverage::EveryPixel, double share = 1.0) {
        return Add({slot, p, Access::Read, c, share});
    }
    Bindings& Write(int slot, PlaneRef p, Coverage c = Coverage::EveryPixel) {
        return Add({slot, p, Access::Write, c});
    }
    Bindings& ReadWrite(int slot, PlaneRef p, Coverage c = Coverage::EveryPixel) {
        return Add({slot, p, Access::ReadWrite, c});
    }
    Bindings& Unused(int slot, PlaneRef p) { return Add({slot, p, Access::Unused}); }
    // `p` read where `used`, else the slot holds a plane nothing reads.
    Bindings& ReadIf(bool used, int slot, PlaneRef p) { return used ? Read(slot, p) : Unused(slot, kUnreadSlot); }
    Bindings& WriteIf(bool used, int slot, PlaneRef p) {
        return used ? Write(slot, p) : Unused(slot, kUnwrittenSlot);
    }
    // A slot the shader loads on every pixel whatever is bound (`bytesPerPixel` each).
    Bindings& Placeholder(int slot, PlaneRef p, double bytesPerPixel) {
        return Add({slot, p, Access::Read, Coverage::EveryPixel, 1.0, bytesPerPixel});
    }
    std::vector<Binding> list;

  private:
    Bindings& Add(Binding b) {
        list.push_back(b);
        return *this;
    }
};

// What every pass builder reads: the variant's flags and the parameters, resolved once.
struct Family {
    const DenoiserVariant& v;
    const DenoiserParams& params;
    const SvgfParams& svgf;
    int width, height;
    std::vector<Channel> channels;  // filtered channels: direct + indirect, or combined
    bool pair;                      // both channels in one dispatch
    bool twoHistoryFamily;          // the two-history family's passes (vs SVGF's)
    int feedback;                   // FeedbackIteration
    ivec2 size, grid;

    Family(const DenoiserVariant& variant, const DenoiserParams& p, int w, int h)
        : v(variant), params(p), svgf(p.svgf), width(w), height(h), channels(FilteredChannels(p.svgf)),
          pair(channels.size() == 2), twoHistoryFamily(variant.family == DenoiserFamily::TwoHistory),
          feedback(FeedbackIteration(p.svgf, variant.twoHistory)), size(w, h), grid(StratumGridSize(w, h)) {}

    Channel First() const { return channels.front(); }
    Channel Last() const { return channels.back(); }
    PipelineKey Pipeline(StageShader shader, Specialization spec = {}, bool pairVariant = false) const {
        return {shader, pairVariant, false, false, params.precision == Precision::Fp16, spec};
    }
    Specialization EdgeStopping() const {
        return Specialization::Of({{FOVRT_SPEC_NORMAL_SQUARINGS, NormalWeightSquarings(svgf.sigmaNormal)}});
    }
};

// Appends passes and their commands, in recording order.
class Writer {
  public:
    explicit Writer(std::vector<PlannedPass>& passes) : passes_(passes) {}
    void Pass(std::string name, std::string referenceTimer, ReferenceStage stage, When when = When::Always) {
        passes_.push_back({std::move(name), when, std::move(referenceTimer), std::move(stage), {}, {}});
    }
    void Dispatch(DispatchCommand d, When when = When::Always) { Add(when, std::move(d)); }
    void Fill(PlaneRef p, uint32_t value, When when = When::Always) { Add(when, FillCommand{p, value}); }
    void Copy(PlaneRef from, PlaneRef to) { Add(When::Always, CopyCommand{from, to}); }
    void Upload(PlaneRef to, PlaneKind staging, Coverage c = Coverage::EveryPixel, When when = When::Always) {
        Add(when, UploadCommand{to, staging, c});
    }
    void Download(PlaneRef from) { Add(When::Always, DownloadCommand{from, PlaneKind::Staging}); }
    void Clear(When when) { Add(when, ClearCommand{}); }
    void Barrier(When when = When::Always) { Add(when, BarrierCommand{}); }

  private:
    template <typename Op>
    void Add(When when, Op op) {
        passes_.back().commands.push_back({when, std::move(op)});
    }
    std::vector<PlannedPass>& passes_;
};

DispatchCommand Over(Grid grid, PipelineKey pipeline, Bindings b, PushBlock push, int step = 1) {
    return {.pipeline = pipeline, .bindings = std::move(b.list), .push = std::move(push), .grid = grid, .step = step};
}
DispatchCommand OverPixels(PipelineKey pipeline, Bindings b, PushBlock push) {
    return Over(Grid::Pixels, pipeline, std::move(b), std::move(push));
}
DispatchCommand OverStrata(PipelineKey pipeline, Bindings b, PushBlock push) {
    return Over(Grid::Strata, pipeline, std::move(b), std::move(push));
}
DispatchCommand OverList(PipelineKey pipeline, Bindings b, PushBlock push, PlaneId args, Coverage listed) {
    return {pipeline, std::move(b.list), std::move(push), Grid::PixelList, 1, args, listed};
}

// Every FrameInputs plane a frame uploads (this frame's geometry into its history side), the
// sample counts where a history weighs by them, A-SVGF's gradient samples; a reset first clears
// every plane. The two-history family stages its per-frame extras apart (staging.extra).
void Upload(Writer& w, const Family& f) {
    w.Pass("upload", "", std::monostate{});
    w.Clear(When::NoPrevious);
    w.Barrier(When::NoPrevious);
    for (PlaneKind kind : PlanesUploadedEveryFrame())
        w.Upload(IsHistory(kind) ? This(kind) : Shared(kind), PlaneKind::Staging);
    w.Fill(Shared(PlaneKind::Stats), 0u);
    const PlaneKind extras = f.twoHistoryFamily ? PlaneKind::StagingExtra : PlaneKind::Staging;
    if (f.v.needsSampleCount) w.Upload(Shared(PlaneKind::SampleCount), extras);
    if (f.v.needsGradientSamples)
        w.Upload(Shared(PlaneKind::AsvgfSamples), extras, Coverage::UploadedSamples, When::GradientSamples);
    w.Barrier();
}

// A-SVGF's temporal gradient at stratum resolution (Schied 2018 §3): claim a slot per stratum
// (first sample wins), gather (δ, Δ) and the stratum guide, σ_l·std of the guide, à-trous
// iterations; then the per-pixel α and λ. Without a previous frame neither runs: the reset left
// α = λ = 1 (ClearValue).
void AsvgfGradient(Writer& w, const Family& f) {
    const int iterations = f.params.asvgf.gradientIterations;
    AsvgfGradientStage stage{{PlaneKind::AsvgfGrad0}, {}};
    for (int i = 0; i < iterations; ++i)
        stage.iterations.push_back({Channel::None, {i & 1 ? PlaneKind::AsvgfGrad1 : PlaneKind::AsvgfGrad0},
                                    {i & 1 ? PlaneKind::AsvgfGrad0 : PlaneKind::AsvgfGrad1}, std::nullopt});
    const PlaneId reconstructed = stage.iterations.empty() ? stage.scattered : stage.iterations.back().out;
    const PlaneRef claim = Shared(PlaneKind::AsvgfClaim), samples = Shared(PlaneKind::AsvgfSamples);
    const PlaneRef guideGeometry = Shared(PlaneKind::AsvgfGuideGeometry);
    const PlaneRef guideLuminance = Shared(PlaneKind::AsvgfGuideLuminance), sigma = Shared(PlaneKind::AsvgfSigma);

    w.Pass("asvgf_gradient", "asvgf_gradient", stage, When::HasPrevious);
    w.Fill(claim, 0xFFFFFFFFu);  // every slot empty
    w.Barrier();
    PushBlock samplesPush = PushBlock::Of(AsvgfSamplesPush{f.size, f.grid, 0u});
    FOVRT_PUSH_PER_FRAME(samplesPush, AsvgfSamplesPush, count, FrameValue::GradientSampleCount);
    Bindings c;  // atomicMin on the claimed slots
    c.Read(ASVGF_CLAIM_B_SAMPLES, samples, Coverage::UploadedSamples)
        .ReadWrite(ASVGF_CLAIM_B_CLAIM, claim, Coverage::ClaimedStrata);
    w.Dispatch(Over(Grid::GradientSamples, f.Pipeline(StageShader::AsvgfClaim), std::move(c), samplesPush),
               When::GradientSamples);
    w.Barrier(When::GradientSamples);
    // The claimed samples → (δ, Δ); the stratum guide from this frame's planes at the guide pixel.
    const Coverage guidePixels = Coverage::StratumGuidePixels;
    Bindings g;
    g.Read(ASVGF_GATHER_B_SAMPLES, samples, Coverage::ClaimedStrata, 0.5)
        .Read(ASVGF_GATHER_B_CLAIM, claim)
        .Write(ASVGF_GATHER_B_GRAD, Shared(stage.scattered.kind))
        .Write(ASVGF_GATHER_B_GUIDE_GEOMETRY, guideGeometry)
        .Write(ASVGF_GATHER_B_GUIDE_LUMINANCE, guideLuminance)
        .Read(ASVGF_GATHER_B_DEPTH, This(PlaneKind::Depth), guidePixels)
        .Read(ASVGF_GATHER_B_NORMAL, This(PlaneKind::Normal), guidePixels)
        .Read(ASVGF_GATHER_B_OBJECT, This(PlaneKind::ObjectId), guidePixels)
        .Read(ASVGF_GATHER_B_DEPTH_GRAD, Shared(PlaneKind::DepthGradient), guidePixels)
        .Read(ASVGF_GATHER_B_DIRECT, Shared(PlaneKind::Direct), guidePixels)
        .Read(ASVGF_GATHER_B_INDIRECT, Shared(PlaneKind::Indirect), guidePixels)
        .Read(ASVGF_GATHER_B_ALBEDO, Shared(PlaneKind::Modulation), guidePixels)
        .Read(ASVGF_GATHER_B_EMISSION, Shared(PlaneKind::Emission), guidePixels);
    w.Dispatch(OverStrata(f.Pipeline(StageShader::AsvgfGather), std::move(g), samplesPush));
    w.Barrier();
    Bindings s;
    s.Read(ASVGF_SIGMA_B_GUIDE_GEOMETRY, guideGeometry)
        .Read(ASVGF_SIGMA_B_GUIDE_LUMINANCE, guideLuminance)
        .Write(ASVGF_SIGMA_B_OUT, sigma);
    w.Dispatch(OverStrata(f.Pipeline(StageShader::AsvgfSigma), std::move(s),
                          PushBlock::Of(AsvgfSigmaPush{f.grid, f.svgf.sigmaLuminance})));
    w.Barrier();
    for (int i = 0; i < iterations; ++i) {
        const StagePlane& it = stage.iterations[size_t(i)];
        Bindings a;
        a.Read(ASVGF_ATROUS_B_GRAD_IN, Shared(it.in.kind))
            .Read(ASVGF_ATROUS_B_GUIDE_GEOMETRY, guideGeometry)
            .Read(ASVGF_ATROUS_B_GUIDE_LUMINANCE, guideLuminance)
            .Read(ASVGF_ATROUS_B_SIGMA, sigma)
            .Write(ASVGF_ATROUS_B_GRAD_OUT, Shared(it.out.kind));
        const AsvgfAtrousPush push{f.size, f.grid, 1 << i, f.svgf.sigmaDepth, f.svgf.sigmaNormal, f.svgf.sigmaLuminance};
        w.Dispatch(OverStrata(f.Pipeline(StageShader::AsvgfAtrous, f.EdgeStopping()), std::move(a), PushBlock::Of(push)));
        w.Barrier();
    }

    w.Pass("asvgf_alpha", "asvgf_gradient", AsvgfAlphaStage{reconstructed}, When::HasPrevious);
    Bindings al;
    al.Read(ASVGF_ALPHA_B_GRAD, Shared(reconstructed.kind))
        .Write(ASVGF_ALPHA_B_ALPHA, Shared(PlaneKind::AsvgfAlpha))
        .Write(ASVGF_ALPHA_B_LAMBDA, Shared(PlaneKind::AsvgfLambda));
    w.Dispatch(OverPixels(f.Pipeline(StageShader::AsvgfAlpha), std::move(al),
                          PushBlock::Of(AsvgfAlphaPush{f.size, f.grid, f.params.asvgf.alpha})));
    w.Barrier();
}

// svgf_pack_guide: this frame's depth, normal, object id → the edge-stopping guide. The shader
// has no history plane, so its fp32 build serves both precisions.
void PackGuide(Writer& w, const Family& f) {
    w.Pass("pack_guide", "", std::monostate{});
    Bindings b;
    b.Read(SVGF_GUIDE_B_DEPTH, This(PlaneKind::Depth))
        .Read(SVGF_GUIDE_B_NORMAL, This(PlaneKind::Normal))
        .Read(SVGF_GUIDE_B_OBJECT, This(PlaneKind::ObjectId))
        .Write(SVGF_GUIDE_B_OUT, Shared(PlaneKind::Guide));
    PipelineKey pipeline = f.Pipeline(StageShader::PackGuide);
    pipeline.fp16 = false;
    w.Dispatch(OverPixels(pipeline, std::move(b), PushBlock::Of(ImageSizePush{f.size})));
    w.Barrier();
}

// The inputs both reprojection shaders bind at slots 0–11 (shaders/bindings/
// reprojection_inputs.h): colour, this frame's and the previous frame's geometry, depth gradient,
// motion, and the list of the pixels whose bilinear taps all failed. The list borrows channel 0's
// spatial-variance list: used up before svgf_moments_classify refills it.
void ReprojectionInputs(Bindings& b, const Family& f) {
    static_assert(SVGF_REPROJECT_B_LIST == TH_REPROJECT_B_LIST && SVGF_REPROJECT_B_COLOR_IN2 == TH_REPROJECT_B_COLOR_IN2);
    b.Read(SVGF_REPROJECT_B_COLOR_IN, Shared(PlaneKind::Direct))
        .Read(SVGF_REPROJECT_B_COLOR_IN2, Shared(PlaneKind::Indirect))
        .Read(SVGF_REPROJECT_B_DEPTH, This(PlaneKind::Depth))
        .Read(SVGF_REPROJECT_B_NORMAL, This(PlaneKind::Normal))
        .Read(SVGF_REPROJECT_B_OBJECT, This(PlaneKind::ObjectId))
        .Read(SVGF_REPROJECT_B_PREV_DEPTH, Previous(PlaneKind::Depth))
        .Read(SVGF_REPROJECT_B_PREV_NORMAL, Previous(PlaneKind::Normal))
        .Read(SVGF_REPROJECT_B_PREV_OBJECT, Previous(PlaneKind::ObjectId))
        .Read(SVGF_REPROJECT_B_DEPTH_GRAD, Shared(PlaneKind::DepthGradient))
        .Read(SVGF_REPROJECT_B_PREV_PIXEL, Shared(PlaneKind::PrevPixel))
        .ReadWrite(SVGF_REPROJECT_B_LIST_ARGS, Scratch(PlaneKind::SpatialArgs, f.First()))
        .Write(SVGF_REPROJECT_B_LIST, Scratch(PlaneKind::SpatialList, f.First()), Coverage::FallbackPixels);
}

// svgf_reproject: per channel the colour, moments, length (and, weighted, total-weight)
// histories; the colour history only without à-trous feedback.
Bindings SvgfReprojectBindings(const Family& f) {
    const bool weighted = f.svgf.weightBySampleCount, writeColor = f.feedback == 0;
    Bindings b;
    ReprojectionInputs(b, f);
    b.ReadIf(weighted, SVGF_REPROJECT_B_SAMPLE_COUNT, Shared(PlaneKind::SampleCount));
    b.ReadWrite(SVGF_REPROJECT_B_STATS, Shared(PlaneKind::Stats));
    for (size_t c = 0; c < f.channels.size(); ++c) {
        const Channel ch = f.channels[c];
        auto slot = [&](int first, int second) { return c == 0 ? first : second; };
        using K = PlaneKind;
        b.Read(slot(SVGF_REPROJECT_B_PREV_COLOR, SVGF_REPROJECT_B_PREV_COLOR2), Previous(K::Color, ch))
            .Read(slot(SVGF_REPROJECT_B_PREV_MOMENTS, SVGF_REPROJECT_B_PREV_MOMENTS2), Previous(K::Moments, ch))
            .Read(slot(SVGF_REPROJECT_B_PREV_LENGTH, SVGF_REPROJECT_B_PREV_LENGTH2), Previous(K::Length, ch))
            .Write(slot(SVGF_REPROJECT_B_CUR_MOMENTS, SVGF_REPROJECT_B_CUR_MOMENTS2), This(K::Moments, ch))
            .Write(slot(SVGF_REPROJECT_B_CUR_LENGTH, SVGF_REPROJECT_B_CUR_LENGTH2), This(K::Length, ch))
            .Write(slot(SVGF_REPROJECT_B_ILLUM_OUT, SVGF_REPROJECT_B_ILLUM_OUT2), Scratch(K::Illum0, ch));
        const int curColor = slot(SVGF_REPROJECT_B_CUR_COLOR, SVGF_REPROJECT_B_CUR_COLOR2);
        if (writeColor) b.Write(curColor, This(K::Color, ch));
        else b.Unused(curColor, This(K::Color, ch));
        // Unweighted, the weight slots hold the length planes, unread.
        const int prevWeight = slot(SVGF_REPROJECT_B_PREV_WEIGHT, SVGF_REPROJECT_B_PREV_WEIGHT2);
        const int curWeight = slot(SVGF_REPROJECT_B_CUR_WEIGHT, SVGF_REPROJECT_B_CUR_WEIGHT2);
        if (weighted) b.Read(prevWeight, Previous(K::Weight, ch)).Write(curWeight, This(K::Weight, ch));
        else b.Unused(prevWeight, Previous(K::Length, ch)).Unused(curWeight, This(K::Length, ch));
    }
    return b;
}

// two_history_reproject: both histories (I_u, and for two-history I_w, W_w, S_k, g), A-SVGF's
// per-pixel α; W_u (channel 0's length) gathered once for both channels.
Bindings TwoHistoryReprojectBindings(const Family& f) {
    using K = PlaneKind;
    const bool two = f.v.twoHistory, ema = f.v.emaGradient, writeColor = f.feedback == 0;
    const Channel ch0 = f.First(), ch1 = f.Last();
    Bindings b;
    ReprojectionInputs(b, f);
    if (two) b.Read(TH_REPROJECT_B_SAMPLE_COUNT, Shared(K::SampleCount));
    else b.Placeholder(TH_REPROJECT_B_SAMPLE_COUNT, kUnreadSlot, 2.0);  // loaded on every pixel
    b.ReadIf(f.v.asvgfGradient, TH_REPROJECT_B_ALPHA, Shared(K::AsvgfAlpha))
        .Read(TH_REPROJECT_B_PREV_IU, Previous(K::Color, ch0))
        .Read(TH_REPROJECT_B_PREV_M, Previous(K::Moments, ch0))
        .Read(TH_REPROJECT_B_PREV_WU, Previous(K::Length, ch0))
        .ReadIf(two, TH_REPROJECT_B_PREV_IW, Previous(K::WColor, ch0))
        .ReadIf(two, TH_REPROJECT_B_PREV_WW, Previous(K::WWeight))
        .ReadIf(two, TH_REPROJECT_B_PREV_S, Previous(K::PowerSums))
        .ReadIf(ema, TH_REPROJECT_B_PREV_G, Previous(K::Gradient))
        .Write(TH_REPROJECT_B_CUR_M, This(K::Moments, ch0))
        .Write(TH_REPROJECT_B_CUR_WU, This(K::Length, ch0))
        .Write(TH_REPROJECT_B_ILLUM_U, Scratch(K::Illum0, ch0))
        .WriteIf(two, TH_REPROJECT_B_CUR_WW, This(K::WWeight))
        .WriteIf(two, TH_REPROJECT_B_CUR_S, This(K::PowerSums))
        .WriteIf(ema, TH_REPROJECT_B_CUR_G, This(K::Gradient))
        .WriteIf(two, TH_REPROJECT_B_ILLUM_W, Scratch(K::WIllum0, ch0))
        .ReadWrite(TH_REPROJECT_B_STATS, Shared(K::Stats));
    // The colour histories: written here only without à-trous feedback.
    auto colorHistory = [&](int slot, K kind, Channel ch) {
        if (kind == K::WColor && !two) b.Unused(slot, kUnwrittenSlot);
        else if (writeColor) b.Write(slot, This(kind, ch));
        else b.Unused(slot, This(kind, ch));
    };
    colorHistory(TH_REPROJECT_B_CUR_IU, K::Color, ch0);
    colorHistory(TH_REPROJECT_B_CUR_IW, K::WColor, ch0);
    if (!f.pair) {
        b.Unused(TH_REPROJECT_B_PREV_IU_OTHER, Previous(K::Color, ch0));
        return b;
    }
    b.Read(TH_REPROJECT_B_PREV_IU_OTHER, Previous(K::Color, ch1))
        .ReadIf(two, TH_REPROJECT_B_PREV_IW2, Previous(K::WColor, ch1))
        .Read(TH_REPROJECT_B_PREV_M2, Previous(K::Moments, ch1))
        .Unused(TH_REPROJECT_B_PREV_WU2, Previous(K::Length, ch1))
        .Write(TH_REPROJECT_B_CUR_M2, This(K::Moments, ch1))
        .Write(TH_REPROJECT_B_CUR_WU2, This(K::Length, ch1))
        .Write(TH_REPROJECT_B_ILLUM_U2, Scratch(K::Illum0, ch1))
        .WriteIf(two, TH_REPROJECT_B_ILLUM_W2, Scratch(K::WIllum0, ch1));
    colorHistory(TH_REPROJECT_B_CUR_IU2, K::Color, ch1);
    colorHistory(TH_REPROJECT_B_CUR_IW2, K::WColor, ch1);
    return b;
}

// Temporal accumulation as two passes of one shader (shaders/common/reprojection.glsl): every
// pixel with the bilinear taps, listing the pixels whose taps all failed, then the "_box" variant
// with the 3×3 fallback taps over the listed pixels only (indirect; lavapipe runs masked-off code
// anyway). Mode bits are a specialization constant of both.
void Reproject(Writer& w, const Family& f) {
    const bool th = f.twoHistoryFamily;
    ReprojectStage stage{th, {}};
    const bool writeColor = f.feedback == 0;
    auto output = [&](PlaneKind illum, PlaneKind history, Channel ch) {
        stage.outputs.push_back({ch, {}, {illum, ch}, writeColor ? std::optional(This(history, ch)) : std::nullopt});
    };
    for (Channel ch : f.channels) output(PlaneKind::Illum0, PlaneKind::Color, ch);
    if (f.v.twoHistory)
        for (Channel ch : f.channels) output(PlaneKind::WIllum0, PlaneKind::WColor, ch);

    uint32_t flags = 0;
    PushBlock push;
    Bindings b;
    if (th) {
        flags = (f.v.twoHistory ? TH_REPROJECT_FLAG_TWO_HISTORY : 0u) | (f.v.emaGradient ? TH_REPROJECT_FLAG_GRADIENT : 0u) |
                (f.pair ? 0u : TH_REPROJECT_FLAG_COMBINED) | (f.v.asvgfGradient ? TH_REPROJECT_FLAG_ALPHA_MAP : 0u) |
                (writeColor ? TH_REPROJECT_FLAG_WRITE_COLOR : 0u);
        push = PushBlock::Of(TwoHistoryReprojectPush{f.size, f.svgf.alphaColor, f.svgf.alphaMoments,
                                                     f.params.twoHistory.gradientBeta, 0u});
        FOVRT_PUSH_PER_FRAME(push, TwoHistoryReprojectPush, has_prev, FrameValue::HasPrevious);
        b = TwoHistoryReprojectBindings(f);
    } else {
        flags = (f.svgf.weightBySampleCount ? SVGF_REPROJECT_FLAG_WEIGHTED : 0u) |
                (f.svgf.filterCombined ? SVGF_REPROJECT_FLAG_COMBINED : 0u) |
                (writeColor ? SVGF_REPROJECT_FLAG_WRITE_COLOR : 0u);
        push = PushBlock::Of(SvgfReprojectPush{f.size, f.svgf.alphaColor, f.svgf.alphaMoments, 0u});
        FOVRT_PUSH_PER_FRAME(push, SvgfReprojectPush, has_prev, FrameValue::HasPrevious);
        b = SvgfReprojectBindings(f);
    }
    const StageShader shader = th ? StageShader::TwoHistoryReproject : StageShader::SvgfReproject;
    const PipelineKey main = f.Pipeline(shader, Specialization::Of({{FOVRT_SPEC_REPROJECT_FLAGS, int32_t(flags)}}), f.pair);
    PipelineKey box = main;
    box.box = true;
    const PlaneId listArgs{PlaneKind::SpatialArgs, f.First()};

    w.Pass(th ? "two_history_reproject" : "reproject", th ? "two_history_reproject" : "reproject", stage);
    w.Fill(Scratch(listArgs.kind, listArgs.channel), 0u);
    w.Barrier();
    w.Dispatch(OverPixels(main, b, push));
    w.Barrier();
    // Without a previous frame nothing is listed.
    w.Dispatch(OverList(box, b, push, listArgs, Coverage::FallbackPixels), When::HasPrevious);
    w.Barrier(When::HasPrevious);
}

// The pixels whose history is shorter than the threshold get the 7×7 spatial variance estimate
// of each plane (svgf_moments_classify lists them, svgf_filter_moments runs indirect over the
// list); every other pixel is copied through. One list per channel serves both its planes (I_u
// and I_w test the same W_u).
void FilterMoments(Writer& w, const Family& f) {
    using K = PlaneKind;
    FilterMomentsStage stage;
    for (Channel ch : f.channels) {
        stage.planes.push_back({ch, {K::Illum0, ch}, {K::Illum1, ch}, std::nullopt});
        if (f.v.twoHistory) stage.planes.push_back({ch, {K::WIllum0, ch}, {K::WIllum1, ch}, std::nullopt});
    }
    const float threshold = float(f.svgf.varianceHistoryThreshold);
    w.Pass("filter_moments", "filter_moments", stage);
    for (Channel ch : f.channels) w.Fill(Scratch(K::SpatialArgs, ch), 0u);
    w.Barrier();
    for (Channel ch : f.channels) {
        Bindings k;
        k.Read(SVGF_CLASSIFY_B_GUIDE, Shared(K::Guide))
            .Read(SVGF_CLASSIFY_B_LENGTH, This(K::Length, ch))
            .ReadWrite(SVGF_CLASSIFY_B_ARGS, Scratch(K::SpatialArgs, ch))
            .Write(SVGF_CLASSIFY_B_LIST, Scratch(K::SpatialList, ch), Coverage::ListedPixels);
        w.Dispatch(OverPixels(f.Pipeline(StageShader::MomentsClassify), std::move(k),
                              PushBlock::Of(SvgfClassifyPush{f.size, threshold})));
        for (const StagePlane& p : stage.planes)
            if (p.channel == ch) w.Copy(Scratch(p.in.kind, ch), Scratch(p.out.kind, ch));
    }
    w.Barrier();
    const PushBlock push = PushBlock::Of(SvgfFilterMomentsPush{f.size, f.svgf.sigmaDepth, f.svgf.sigmaNormal, threshold});
    for (const StagePlane& p : stage.planes) {
        Bindings m;
        m.Read(SVGF_MOMENTS_B_ILLUM_IN, Scratch(p.in.kind, p.channel))
            .Read(SVGF_MOMENTS_B_GUIDE, Shared(K::Guide))
            .Read(SVGF_MOMENTS_B_DEPTH_GRAD, Shared(K::DepthGradient))
            .Read(SVGF_MOMENTS_B_MOMENTS, This(K::Moments, p.channel))
            .Read(SVGF_MOMENTS_B_LENGTH, This(K::Length, p.channel))
            .Write(SVGF_MOMENTS_B_ILLUM_OUT, Scratch(p.out.kind, p.channel))
            .ReadWrite(SVGF_MOMENTS_B_ARGS, Scratch(K::SpatialArgs, p.channel))
            .Read(SVGF_MOMENTS_B_LIST, Scratch(K::SpatialList, p.channel));
        w.Dispatch(OverList(f.Pipeline(StageShader::FilterMoments, f.EdgeStopping()), std::move(m), push,
                            {K::SpatialArgs, p.channel}, Coverage::ListedPixels));
    }
    w.Barrier();
}

// two-history's EMA gradient g, filtered 5×5 on the packed guide, against each channel's variance → q.
void EmaGradient(Writer& w, const Family& f) {
    using K = PlaneKind;
    EmaGradientStage stage;
    for (Channel ch : f.channels) stage.illumination.push_back({K::Illum1, ch});
    w.Pass("two_history_gradient", "two_history_gradient", stage);
    Bindings b;
    b.Read(TH_GRADIENT_B_GRADIENT, This(K::Gradient))
        .Read(TH_GRADIENT_B_ILLUM_U0, Scratch(K::Illum1, f.First()))
        .Read(TH_GRADIENT_B_GUIDE, Shared(K::Guide))
        .Read(TH_GRADIENT_B_DEPTH_GRAD, Shared(K::DepthGradient))
        .Write(TH_GRADIENT_B_Q, Shared(K::Q));
    if (f.pair) b.Read(TH_GRADIENT_B_ILLUM_U1, Scratch(K::Illum1, f.Last()));
    else b.Unused(TH_GRADIENT_B_ILLUM_U1, Scratch(K::Illum1, f.First()));
    const TwoHistoryGradientPush push{f.size, f.svgf.sigmaDepth, f.svgf.sigmaNormal, f.params.twoHistory.qScale,
                                      f.pair ? 1u : 0u};
    w.Dispatch(OverPixels(f.Pipeline(StageShader::TwoHistoryGradient, f.EdgeStopping()), std::move(b),
                          PushBlock::Of(push)));
    w.Barrier();
}

// two_history_blend per channel, in place on I_u: lerp(I_w, I_u, lerp(q, 1, p)) with p from W_u
// (channel 0's length), W_w and S.
void Blend(Writer& w, const Family& f, PlaneKind unweighted, PlaneKind weighted) {
    using K = PlaneKind;
    BlendStage stage{{}, BlendQPlane(f.v)};
    for (Channel ch : f.channels) stage.planes.push_back({ch, {weighted, ch}, {unweighted, ch}, std::nullopt});
    w.Pass("two_history_blend", "atrous_blend", stage);
    for (const StagePlane& p : stage.planes) {
        Bindings b;
        b.ReadWrite(TH_BLEND_B_ILLUM_U, Scratch(unweighted, p.channel))
            .Read(TH_BLEND_B_ILLUM_W, Scratch(weighted, p.channel))
            .Read(TH_BLEND_B_WU, This(K::Length, f.First()))
            .Read(TH_BLEND_B_WW, This(K::WWeight))
            .Read(TH_BLEND_B_S, This(K::PowerSums))
            .Read(TH_BLEND_B_Q, Shared(stage.q.kind));
        w.Dispatch(OverPixels(f.Pipeline(StageShader::TwoHistoryBlend), std::move(b), PushBlock::Of(ImageSizePush{f.size})));
    }
    w.Barrier();
}

// À-trous iteration i (step 2^i) of every channel's I_u (and, at iteration 0 of two-history, I_w):
// illumination ping-pong plane (i+1)&1 → i&1, the colour history written on the feedback
// iteration. Planes go two per dispatch ("_pair": the guide fetches and the w_z·w_n exponent
// shared), one invocation per 2×2 block ("_step1" at step 1: the four 3×3 variance windows form
// one 4×4 block).
void Atrous(Writer& w, const Family& f, int i) {
    using K = PlaneKind;
    struct Filtered {
        StagePlane plane;
        K history;  // the colour history of this plane, bound whether or not written
    };
    const bool both = f.v.twoHistory && i == 0;  // iteration 0 filters I_u and I_w
    const bool feedback = i + 1 == f.feedback;
    std::vector<Filtered> planes;
    auto add = [&](K even, K odd, K history) {
        for (Channel ch : f.channels)
            planes.push_back({{ch, {(i + 1) & 1 ? odd : even, ch}, {i & 1 ? odd : even, ch},
                               feedback ? std::optional(This(history, ch)) : std::nullopt},
                              history});
    };
    add(K::Illum0, K::Illum1, K::Color);
    if (both) add(K::WIllum0, K::WIllum1, K::WColor);
    AtrousStage stage{i, {}};
    for (const Filtered& p : planes) stage.planes.push_back(p.plane);

    const std::string name = fmt::format("atrous{}", i);
    // The two-history family's reference reports its à-trous iterations and blend as one timer.
    w.Pass(name, f.twoHistoryFamily ? "atrous_blend" : name, stage);
    const SvgfAtrousPush push{f.size, 1 << i, f.svgf.sigmaDepth, f.svgf.sigmaNormal, f.svgf.sigmaLuminance};
    for (size_t first = 0; first < planes.size(); first += 2) {
        const bool pairDispatch = first + 1 < planes.size();
        Bindings b;
        b.Read(SVGF_ATROUS_B_GUIDE, Shared(K::Guide)).Read(SVGF_ATROUS_B_DEPTH_GRAD, Shared(K::DepthGradient));
        for (size_t k = 0; k < (pairDispatch ? 2u : 1u); ++k) {
            const Filtered& p = planes[first + k];
            const Channel ch = p.plane.channel;
            b.Read(k ? SVGF_ATROUS_B_ILLUM_IN2 : SVGF_ATROUS_B_ILLUM_IN, Scratch(p.plane.in.kind, ch))
                .Write(k ? SVGF_ATROUS_B_ILLUM_OUT2 : SVGF_ATROUS_B_ILLUM_OUT, Scratch(p.plane.out.kind, ch));
            const int historySlot = k ? SVGF_ATROUS_B_HIST_COLOR2 : SVGF_ATROUS_B_HIST_COLOR;
            if (feedback) b.Write(historySlot, This(p.history, ch));
            else b.Unused(historySlot, This(p.history, ch));
        }
        w.Dispatch(Over(Grid::AtrousBlocks, AtrousPipeline(f.params, pairDispatch, i == 0, feedback), std::move(b),
                        PushBlock::Of(push), 1 << i));
    }
    w.Barrier();
    if (both) Blend(w, f, K::Illum0, K::WIllum0);
}

// svgf_modulate: Modulation()·(filtered direct + indirect) + emission → output, then downloaded
// with the sanitising counters.
void ModulateAndDownload(Writer& w, const Family& f) {
    using K = PlaneKind;
    const K last = FilteredIlluminationPlane(f.svgf.atrousIterations) ? K::Illum1 : K::Illum0;
    ModulateStage stage;
    for (Channel ch : f.channels) stage.illumination.push_back({last, ch});
    w.Pass("modulate", "modulate", stage);
    Bindings b;
    b.Read(SVGF_MODULATE_B_ILLUM0, Scratch(last, f.First()))
        .Read(SVGF_MODULATE_B_ALBEDO, Shared(K::Modulation))
        .Read(SVGF_MODULATE_B_EMISSION, Shared(K::Emission))
        .Write(SVGF_MODULATE_B_OUT, Shared(K::Output));
    if (f.pair) b.Read(SVGF_MODULATE_B_ILLUM1, Scratch(last, f.Last()));
    else b.Unused(SVGF_MODULATE_B_ILLUM1, Scratch(last, f.First()));  // combined: one channel holds both
    const Specialization combined = Specialization::Of({{FOVRT_SPEC_MODULATE_COMBINED, f.pair ? 0 : 1}});
    w.Dispatch(OverPixels(f.Pipeline(StageShader::Modulate, combined), std::move(b), PushBlock::Of(ImageSizePush{f.size})));
    w.Barrier();

    w.Pass("download", "", std::monostate{});
    w.Download(Shared(K::Output));
    w.Download(Shared(K::Stats));
    w.Barrier();
}

}  // namespace

PipelineKey AtrousPipeline(const DenoiserParams& params, bool pair, bool step1, bool writeHistory, bool unitWeights) {
    const Specialization spec = Specialization::Of({{FOVRT_SPEC_NORMAL_SQUARINGS, NormalWeightSquarings(params.svgf.sigmaNormal)},
                                                    {FOVRT_SPEC_ATROUS_WRITE_HISTORY, writeHistory ? 1 : 0},
                                                    {FOVRT_SPEC_ATROUS_UNIT_WEIGHTS, unitWeights ? 1 : 0}});
    return {StageShader::Atrous, pair, step1, false, params.precision == Precision::Fp16, spec};
}

int32_t NormalWeightSquarings(float sigmaNormal) {
    for (int k = 0; k <= FOVRT_MAX_NORMAL_SQUARINGS; ++k)
        if (sigmaNormal == float(1 << k)) return k;
    return -1;
}

PlaneId BlendQPlane(const DenoiserVariant& variant) {
    return {variant.emaGradient ? PlaneKind::Q : PlaneKind::AsvgfLambda, Channel::None};
}

std::vector<PlannedPass> PlanSvgfFamily(const DenoiserVariant& variant, const DenoiserParams& params, int width,
                                        int height) {
    const Family f(variant, params, width, height);
    std::vector<PlannedPass> passes;
    Writer w(passes);
    Upload(w, f);
    if (variant.asvgfGradient) AsvgfGradient(w, f);
    PackGuide(w, f);
    Reproject(w, f);
    FilterMoments(w, f);
    if (variant.emaGradient) EmaGradient(w, f);
    // Without à-trous the blend follows the variance estimate.
    if (variant.twoHistory && f.svgf.atrousIterations == 0) Blend(w, f, PlaneKind::Illum1, PlaneKind::WIllum1);
    for (int i = 0; i < f.svgf.atrousIterations; ++i) Atrous(w, f, i);
    ModulateAndDownload(w, f);
    return passes;
}

}  // namespace fovrt
