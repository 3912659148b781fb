// The plan fragments of two-history's mechanisms with passes of their own (denoise/mechanism_passes.h):
// the EMA gradient, the held choice, the stabilisation.
#include "denoise/mechanism_passes.h"

#include "core/error.h"
#include "denoise/plan_writer.h"

namespace fovrt::plan {

// two-history's EMA gradient g, filtered 5×5 on the packed guide, against each channel's variance → q.
void EmaGradient(Writer& w, const Family& f, FrameCursor&) {
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

namespace {

// The eight planes a pass's own bilinear reprojection reads (common/reprojection.glsl): this
// frame's and the previous frame's depth, normal and object id, the depth gradient and the
// previous pixel, at consecutive slots from `depthSlot` in that order (the binding lists of
// two_history_stabilize and two_history_choice; checked below).
#define FOVRT_REPROJECTION_GEOMETRY_SLOTS(P)                                                        \
    static_assert(P##_B_NORMAL == P##_B_DEPTH + 1 && P##_B_OBJECT == P##_B_DEPTH + 2 &&             \
                  P##_B_PREV_DEPTH == P##_B_DEPTH + 3 && P##_B_PREV_NORMAL == P##_B_DEPTH + 4 &&    \
                  P##_B_PREV_OBJECT == P##_B_DEPTH + 5 && P##_B_DEPTH_GRAD == P##_B_DEPTH + 6 &&    \
                  P##_B_PREV_PIXEL == P##_B_DEPTH + 7)
FOVRT_REPROJECTION_GEOMETRY_SLOTS(TH_STABILIZE);
FOVRT_REPROJECTION_GEOMETRY_SLOTS(TH_CHOICE);
#undef FOVRT_REPROJECTION_GEOMETRY_SLOTS

void ReadReprojectionGeometry(Bindings& b, int depthSlot, const Family& f) {
    using K = PlaneKind;
    b.Read(depthSlot, This(K::Depth))
        .Read(depthSlot + 1, This(K::Normal))
        .ReadObjectIds(depthSlot + 2, This(K::ObjectId), f.idsInDepth)
        .Read(depthSlot + 3, Previous(K::Depth))
        .Read(depthSlot + 4, Previous(K::Normal))
        .ReadObjectIds(depthSlot + 5, Previous(K::ObjectId), f.idsInDepth)
        .Read(depthSlot + 6, Shared(K::DepthGradient))
        .Read(depthSlot + 7, Shared(K::PrevPixel));
}

}  // namespace

// two_history_choice (the hysteresis variants), once per frame before the blend: p from W_u, W_w
// and S, held against the reprojected previous choice (HystereticChoice) → this frame's choice.
void HeldChoice(Writer& w, const Family& f, FrameCursor&) {
    using K = PlaneKind;
    w.Pass("two_history_choice", "two_history_choice", ChoiceStage{});
    const TwoHistoryParams& t = f.params.twoHistory;
    PushBlock push = PushBlock::Of(TwoHistoryChoicePush{f.size, f.window, ivec2(0), t.choiceRate, t.choiceBand, 0u});
    FOVRT_PUSH_PER_FRAME(push, TwoHistoryChoicePush, has_prev, FrameValue::HasPrevious);
    FOVRT_PUSH_WINDOW_ORIGIN(push, TwoHistoryChoicePush, win_origin);
    Bindings b;
    ReadReprojectionGeometry(b, TH_CHOICE_B_DEPTH, f);
    b.Read(TH_CHOICE_B_WU, This(K::Length, f.First()))
        .Read(TH_CHOICE_B_WW, This(K::WWeight))
        .Read(TH_CHOICE_B_S, This(K::PowerSums))
        .Read(TH_CHOICE_B_PREV_CHOICE, Previous(K::Choice))
        .Write(TH_CHOICE_B_CUR_CHOICE, This(K::Choice));
    w.Dispatch(OverPixels(f.Pipeline(StageShader::TwoHistoryChoice), std::move(b), push));
    w.Barrier();
}

// two_history_stabilize per channel (two-history-stable): the filtered plane → the other
// ping-pong plane (free after the last à-trous iteration), which it leaves as the filtered one,
// with each channel's stabilised luminance history.
void Stabilize(Writer& w, const Family& f, FrameCursor& cursor) {
    using K = PlaneKind;
    const K filtered = cursor.filtered;
    const K out = filtered == K::Illum1 ? K::Illum0 : K::Illum1;
    const PlaneId q = BlendQPlane(f.v);  // the change detector, read with stabilize-antilag
    StabilizeStage stage{{}, f.v.stabilizeAntilag ? std::optional(q) : std::nullopt};
    for (Channel ch : f.channels) stage.planes.push_back({ch, {filtered, ch}, {out, ch}, This(K::StableLum, ch)});
    w.Pass("two_history_stabilize", "two_history_stabilize", stage);
    const TwoHistoryStableParams& s = f.params.twoHistoryStable;
    PushBlock push = PushBlock::Of(TwoHistoryStabilizePush{f.size, s.alpha, s.sigmaScale, 0u, s.antilagQ,
                                                           stage.q ? 1u : 0u});
    FOVRT_PUSH_PER_FRAME(push, TwoHistoryStabilizePush, has_prev, FrameValue::HasPrevious);
    for (const StagePlane& p : stage.planes) {
        Bindings b;
        ReadReprojectionGeometry(b, TH_STABILIZE_B_DEPTH, f);
        b.Read(TH_STABILIZE_B_ILLUM_IN, Scratch(filtered, p.channel))
            .Write(TH_STABILIZE_B_ILLUM_OUT, Scratch(out, p.channel))
            .Read(TH_STABILIZE_B_WU, This(K::Length, f.First()))
            .Read(TH_STABILIZE_B_PREV_STABLE, Previous(K::StableLum, p.channel))
            .Write(TH_STABILIZE_B_CUR_STABLE, This(K::StableLum, p.channel));
        b.ReadIf(stage.q.has_value(), TH_STABILIZE_B_Q, Shared(q.kind));
        w.Dispatch(OverPixels(f.Pipeline(StageShader::TwoHistoryStabilize), std::move(b), push));
    }
    w.Barrier();
    cursor.filtered = out;
}

PlanFragment FragmentOf(MechanismPass pass) {
    switch (pass) {
        case MechanismPass::AsvgfGradient: return AsvgfGradient;
        case MechanismPass::EmaGradient: return EmaGradient;
        case MechanismPass::HeldChoice: return HeldChoice;
        case MechanismPass::Stabilize: return Stabilize;
        case MechanismPass::None: break;
    }
    Fail("plan: no fragment for mechanism pass {}", int(pass));
}

void EmitMechanismPasses(Writer& w, const Family& f, FrameSlot slot, FrameCursor& cursor) {
    for (MechanismPass pass : MechanismPassesAt(f.v, slot)) FragmentOf(pass)(w, f, cursor);
}

}  // namespace fovrt::plan
