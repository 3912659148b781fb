#include "denoise/plan_writer.h"

// Temporal accumulation (Schied et al. 2017, §4.1; Tu 2024): svgf_reproject for the SVGF family,
// two_history_reproject for the two-history family; their bindings, and the two passes that record
// either.
namespace fovrt::plan {

namespace {

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
        .ReadObjectIds(SVGF_REPROJECT_B_OBJECT, This(PlaneKind::ObjectId), f.idsInDepth)
        .Read(SVGF_REPROJECT_B_PREV_DEPTH, Previous(PlaneKind::Depth))
        .Read(SVGF_REPROJECT_B_PREV_NORMAL, Previous(PlaneKind::Normal))
        .ReadObjectIds(SVGF_REPROJECT_B_PREV_OBJECT, Previous(PlaneKind::ObjectId), f.idsInDepth)
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
    b.ReadIf(f.readsSampleCounts, SVGF_REPROJECT_B_SAMPLE_COUNT, Shared(PlaneKind::SampleCount));
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
    if (f.readsSampleCounts) b.Read(TH_REPROJECT_B_SAMPLE_COUNT, Shared(K::SampleCount));
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
        .Unused(TH_REPROJECT_B_PREV_WU2, kUnreadSlot)  // W_u is shared: channel 0's length (above)
        .Write(TH_REPROJECT_B_CUR_M2, This(K::Moments, ch1))
        .Unused(TH_REPROJECT_B_CUR_WU2, kUnwrittenSlot)
        .Write(TH_REPROJECT_B_ILLUM_U2, Scratch(K::Illum0, ch1))
        .WriteIf(two, TH_REPROJECT_B_ILLUM_W2, Scratch(K::WIllum0, ch1));
    colorHistory(TH_REPROJECT_B_CUR_IU2, K::Color, ch1);
    colorHistory(TH_REPROJECT_B_CUR_IW2, K::WColor, ch1);
    return b;
}

}  // namespace

// Temporal accumulation as two passes of one shader (shaders/common/reprojection.glsl): every
// pixel with the bilinear taps, listing the pixels whose taps all failed, then the "_box" variant
// with the 3×3 fallback taps over the listed pixels only (indirect; lavapipe runs masked-off code
// anyway). Mode bits are a specialization constant of both.
void Reproject(Writer& w, const Family& f) {
    const bool th = f.twoHistoryFamily;
    ReprojectStage stage{th, 0u, {}};
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
                (writeColor ? TH_REPROJECT_FLAG_WRITE_COLOR : 0u) | (f.v.antilag ? TH_REPROJECT_FLAG_ANTILAG : 0u) |
                (f.v.suppressFireflies ? TH_REPROJECT_FLAG_FIREFLY : 0u) |
                (f.zeroSamples ? TH_REPROJECT_FLAG_ZERO_SAMPLES : 0u);
        push = PushBlock::Of(TwoHistoryReprojectPush{f.size, f.svgf.alphaColor, f.svgf.alphaMoments,
                                                     f.params.twoHistory.gradientBeta, 0u,
                                                     f.params.asvgf.antilagPower, f.params.twoHistory.fireflySigma,
                                                     f.window, ivec2(0), ivec2(0)});
        FOVRT_PUSH_PER_FRAME(push, TwoHistoryReprojectPush, has_prev, FrameValue::HasPrevious);
        FOVRT_PUSH_WINDOW_ORIGIN(push, TwoHistoryReprojectPush, win_origin);
        FOVRT_PUSH_PREV_WINDOW_ORIGIN(push, TwoHistoryReprojectPush, prev_win_origin);
        b = TwoHistoryReprojectBindings(f);
    } else {
        flags = (f.svgf.weightBySampleCount ? SVGF_REPROJECT_FLAG_WEIGHTED : 0u) |
                (f.svgf.filterCombined ? SVGF_REPROJECT_FLAG_COMBINED : 0u) |
                (writeColor ? SVGF_REPROJECT_FLAG_WRITE_COLOR : 0u) |
                (f.zeroSamples ? SVGF_REPROJECT_FLAG_ZERO_SAMPLES : 0u);
        push = PushBlock::Of(SvgfReprojectPush{f.size, f.svgf.alphaColor, f.svgf.alphaMoments, 0u});
        FOVRT_PUSH_PER_FRAME(push, SvgfReprojectPush, has_prev, FrameValue::HasPrevious);
        b = SvgfReprojectBindings(f);
    }
    stage.flags = flags;
    const StageShader shader = th ? StageShader::TwoHistoryReproject : StageShader::SvgfReproject;
    const PipelineKey main = f.Pipeline(shader, Specialization::Of({{FOVRT_SPEC_REPROJECT_FLAGS, int32_t(flags)}}), f.pair);
    PipelineKey box = main;
    box.box = true;
    const PlaneId listArgs{PlaneKind::SpatialArgs, f.First()};

    // The timer says what the pass keeps, not which shader runs it: A-SVGF reprojects one history
    // (as SVGF does) through the two-history family's shader, so its pass is "reproject".
    const char* timer = f.v.twoHistory ? "two_history_reproject" : "reproject";
    w.Pass(timer, timer, stage);
    w.Fill(Scratch(listArgs.kind, listArgs.channel), 0u);
    w.Barrier();
    w.Dispatch(OverPixels(main, b, push));
    w.Barrier();
    // Without a previous frame nothing is listed.
    w.Dispatch(OverList(box, b, push, listArgs, Coverage::FallbackPixels), When::HasPrevious);
    w.Barrier(When::HasPrevious);
}

}  // namespace fovrt::plan
