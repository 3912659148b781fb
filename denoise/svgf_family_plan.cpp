#include "denoise/svgf_family_plan.h"

#include <fmt/format.h>

#include "denoise/plan_writer.h"

namespace fovrt {

namespace plan {
namespace {

// Every FrameInputs plane a frame uploads (this frame's geometry into its history side), the
// sample counts where a history weighs by them or the map may hold zeros, A-SVGF's gradient
// samples; a reset first clears every plane.
void Upload(Writer& w, const Family& f) {
    w.Pass("upload", "", std::monostate{});
    w.Clear(When::NoPrevious);
    w.Barrier(When::NoPrevious);
    for (PlaneKind kind : PlanesUploadedEveryFrame(f.params.precision))
        w.Upload(IsHistory(kind) ? This(kind) : Shared(kind));
    w.Fill(Shared(PlaneKind::Stats), 0u);
    if (f.readsSampleCounts) w.Upload(Shared(PlaneKind::SampleCount));
    if (f.v.needsGradientSamples)
        w.Upload(Shared(PlaneKind::AsvgfSamples), Coverage::UploadedSamples, When::GradientSamples);
    w.Barrier();
}

// svgf_pack_guide: this frame's depth, normal, object id → the edge-stopping guide (fp32 in both
// precisions; the _fp16 build decodes the octahedral normals).
void PackGuide(Writer& w, const Family& f) {
    w.Pass("pack_guide", "", std::monostate{});
    Bindings b;
    b.Read(SVGF_GUIDE_B_DEPTH, This(PlaneKind::Depth))
        .Read(SVGF_GUIDE_B_NORMAL, This(PlaneKind::Normal))
        .ReadObjectIds(SVGF_GUIDE_B_OBJECT, This(PlaneKind::ObjectId), f.idsInDepth)
        .Write(SVGF_GUIDE_B_OUT, Shared(PlaneKind::Guide));
    w.Dispatch(OverPixels(f.Pipeline(StageShader::PackGuide), std::move(b), PushBlock::Of(ImageSizePush{f.size})));
    w.Barrier();
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
            .Read(SVGF_CLASSIFY_B_LENGTH, This(K::Length, f.LengthOf(ch)))
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
            .Read(SVGF_MOMENTS_B_LENGTH, This(K::Length, f.LengthOf(p.channel)))
            .Write(SVGF_MOMENTS_B_ILLUM_OUT, Scratch(p.out.kind, p.channel))
            .ReadWrite(SVGF_MOMENTS_B_ARGS, Scratch(K::SpatialArgs, p.channel))
            .Read(SVGF_MOMENTS_B_LIST, Scratch(K::SpatialList, p.channel));
        w.Dispatch(OverList(f.Pipeline(StageShader::FilterMoments, f.EdgeStopping()), std::move(m), push,
                            {K::SpatialArgs, p.channel}, Coverage::ListedPixels));
    }
    w.Barrier();
}

// two_history_blend per channel, in place on I_u: lerp(I_w, I_u, lerp(q, 1, p)) with p from W_u
// (channel 0's length), W_w and S; the clamp variants' box in place of p; the hysteresis variants
// read their held choice (two_history_choice, run first) in place of p.
void Blend(Writer& w, const Family& f, PlaneKind unweighted, PlaneKind weighted) {
    using K = PlaneKind;
    const bool held = f.v.hystereticChoice;
    BlendStage stage{{}, BlendQPlane(f.v), f.v.clampHistory, held ? std::optional(This(K::Choice)) : std::nullopt};
    FrameCursor cursor;
    EmitMechanismPasses(w, f, FrameSlot::BeforeBlend, cursor);
    for (Channel ch : f.channels) stage.planes.push_back({ch, {weighted, ch}, {unweighted, ch}, std::nullopt});
    w.Pass("two_history_blend", "atrous_blend", stage);
    for (const StagePlane& p : stage.planes) {
        Bindings b;
        b.ReadWrite(TH_BLEND_B_ILLUM_U, Scratch(unweighted, p.channel))
            .Read(TH_BLEND_B_ILLUM_W, Scratch(weighted, p.channel))
            .ReadIf(!held, TH_BLEND_B_WU, This(K::Length, f.First()))
            .ReadIf(!held, TH_BLEND_B_WW, This(K::WWeight))
            .ReadIf(!held, TH_BLEND_B_S, This(K::PowerSums))
            .Read(TH_BLEND_B_Q, Shared(stage.q.kind))
            .ReadIf(held, TH_BLEND_B_CHOICE, This(K::Choice));
        PushBlock push = PushBlock::Of(TwoHistoryBlendPush{f.size, f.window, ivec2(0), f.params.twoHistory.clampSigma,
                                                           stage.clamp ? 1u : 0u, held ? 1u : 0u});
        FOVRT_PUSH_WINDOW_ORIGIN(push, TwoHistoryBlendPush, win_origin);
        w.Dispatch(OverPixels(f.Pipeline(StageShader::TwoHistoryBlend), std::move(b), std::move(push)));
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
    for (size_t first = 0; first < planes.size(); first += 2) {
        const bool pairDispatch = first + 1 < planes.size();
        // Each side's fed-back history: the image, or the weighted history's window (its corner
        // set per frame).
        SvgfAtrousPush fields{f.size, 1 << i, f.svgf.sigmaDepth, f.svgf.sigmaNormal, f.svgf.sigmaLuminance,
                              f.size, ivec2(0), f.size, ivec2(0)};
        const bool windowed0 = IsWindowed(planes[first].history);
        const bool windowed1 = pairDispatch && IsWindowed(planes[first + 1].history);
        if (windowed0) fields.hist_size0 = f.window;
        if (windowed1) fields.hist_size1 = f.window;
        PushBlock push = PushBlock::Of(fields);
        if (windowed0) FOVRT_PUSH_WINDOW_ORIGIN(push, SvgfAtrousPush, hist_origin0);
        if (windowed1) FOVRT_PUSH_WINDOW_ORIGIN(push, SvgfAtrousPush, hist_origin1);
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
                        std::move(push), 1 << i));
    }
    w.Barrier();
    if (both) Blend(w, f, K::Illum0, K::WIllum0);
}

// svgf_modulate: Modulation()·(filtered direct + indirect) + emission → output, then downloaded
// with the sanitising counters.
void ModulateAndDownload(Writer& w, const Family& f) {
    using K = PlaneKind;
    FrameCursor cursor{FilteredIlluminationPlane(f.svgf.atrousIterations) ? K::Illum1 : K::Illum0};
    EmitMechanismPasses(w, f, FrameSlot::AfterFilter, cursor);
    const K last = cursor.filtered;
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
}  // namespace plan

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
    using namespace plan;
    const Family f(variant, params, width, height);
    std::vector<PlannedPass> passes;
    Writer w(passes);
    Upload(w, f);
    FrameCursor cursor;
    EmitMechanismPasses(w, f, FrameSlot::BeforeGuide, cursor);
    PackGuide(w, f);
    Reproject(w, f);
    FilterMoments(w, f);
    EmitMechanismPasses(w, f, FrameSlot::AfterVariance, cursor);
    // Without à-trous the blend follows the variance estimate.
    if (variant.twoHistory && f.svgf.atrousIterations == 0) Blend(w, f, PlaneKind::Illum1, PlaneKind::WIllum1);
    for (int i = 0; i < f.svgf.atrousIterations; ++i) Atrous(w, f, i);
    ModulateAndDownload(w, f);
    return passes;
}

}  // namespace fovrt
