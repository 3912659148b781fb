#include "denoise/reference/svgf_family_ref.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <utility>

#include "core/check.h"
#include "core/error.h"
#include "denoise/reference/two_history_math.h"
#include "denoise/svgf_family_plan.h"
#include "shaders/shared_constants.h"

namespace fovrt {

namespace {

size_t IllumIndex(PlaneKind kind) {
    switch (kind) {
        case PlaneKind::Illum0: return 0;
        case PlaneKind::Illum1: return 1;
        case PlaneKind::WIllum0: return 2;
        case PlaneKind::WIllum1: return 3;
        default: Fail("reference: plane kind {} is not an illumination plane", int(kind));
    }
}

size_t GradientIndex(PlaneKind kind) {
    FOVRT_CHECK(kind == PlaneKind::AsvgfGrad0 || kind == PlaneKind::AsvgfGrad1);
    return kind == PlaneKind::AsvgfGrad0 ? 0 : 1;
}

}  // namespace

SvgfFamilyReferenceDenoiser::SvgfFamilyReferenceDenoiser(const DenoiserVariant& variant,
                                                         const DenoiserParams& params)
    : variant_(variant) {
    FOVRT_CHECK(variant.family != DenoiserFamily::Rae);
    SetParams(params);
}

void SvgfFamilyReferenceDenoiser::Reset() {
    width_ = height_ = 0;  // the next Denoise() reallocates every history
    hasFrame_ = false;
}

// As the Vulkan host's Configure: the caller's parameters are range-checked, then the row's
// options are applied to them.
void SvgfFamilyReferenceDenoiser::SetParams(const DenoiserParams& params) {
    ValidateDenoiserParamRanges(params);
    params_ = ParamsForVariant(variant_, params);
    Reset();
}

void SvgfFamilyReferenceDenoiser::Allocate(int width, int height) {
    width_ = width;
    height_ = height;
    plan_ = BuildDenoiserPlan(variant_.name, params_, width, height);
    channels_ = FilteredChannels(params_.svgf);
    twoHistoryLayout_ = false;
    for (const PlannedPass& pass : plan_.passes)
        if (const auto* r = std::get_if<ReprojectStage>(&pass.stage)) twoHistoryLayout_ = r->twoHistory;
    // The state is what the plan names, as the Vulkan host's buffers are: a plane kind the plan's
    // commands never name is not allocated (the window's planes at the plan's window size).
    auto planned = [&](PlaneKind kind) {
        return std::any_of(plan_.planes.begin(), plan_.planes.end(),
                           [&](const PlanePlacement& p) { return p.key.id.kind == kind; });
    };
    const bool weightedHistory = planned(PlaneKind::WColor), stabilised = planned(PlaneKind::StableLum),
               heldChoice = planned(PlaneKind::Choice);
    const ivec2 window = WeightedWindowSize(width, height, WeightedWindowFraction(variant_, params_));
    for (const PlanePlacement& p : plan_.planes)
        if (IsWindowed(p.key.id.kind))
            FOVRT_CHECK(p.bytes == PlaneBytes(p.key.id.kind, {width, height, params_.precision, window}));
    for (int side = 0; side < 2; ++side) {
        if (twoHistoryLayout_) {
            state_[size_t(side)].Allocate(width, height, int(channels_.size()), weightedHistory,
                                          planned(PlaneKind::Gradient), window);
        } else {
            svgf_[size_t(side)].assign(channels_.size(), SvgfHistory{});
            for (SvgfHistory& h : svgf_[size_t(side)]) h.Allocate(width, height, planned(PlaneKind::Weight));
        }
    }
    for (auto& side : stable_)
        for (size_t c = 0; c < side.size(); ++c)
            side[c].Resize(stabilised && c < channels_.size() ? width : 0, stabilised && c < channels_.size() ? height : 0,
                           0.0f);
    for (Plane<float>& side : choice_) side.Resize(heldChoice ? width : 0, heldChoice ? height : 0, 0.0f);
    prevGeometry_.Allocate(width, height);  // background: nothing reprojects
    alpha_ = lambda_ = Plane<float>();
    if (planned(PlaneKind::AsvgfAlpha)) {  // what a reset leaves in α and λ: the gradient needs a previous frame
        alpha_.Resize(width, height, std::bit_cast<float>(ClearValue(PlaneKind::AsvgfAlpha, params_.precision)));
        lambda_.Resize(width, height, std::bit_cast<float>(ClearValue(PlaneKind::AsvgfLambda, params_.precision)));
    }
    hasPrev_ = false;
    hasFrame_ = false;
    parity_ = 0;
}

void SvgfFamilyReferenceDenoiser::Denoise(const FrameInputs& in, Plane<vec3>& output) {
    if (in.width() <= 0 || in.height() <= 0) Fail("{}: empty FrameInputs", Name());
    if (in.cameraCut || in.width() != width_ || in.height() != height_) Allocate(in.width(), in.height());
    timings_.clear();
    using Clock = std::chrono::steady_clock;
    const FrameConditions frame{hasPrev_, !in.gradientSamples.empty()};
    prevWindow_ = hasPrev_ ? window_ : FrameWeightedWindow(variant_, params_, in);
    window_ = FrameWeightedWindow(variant_, params_, in);
    const FrameInputs& stored = StoredInputs(in);
    for (const PlannedPass& pass : plan_.passes) {
        if (!Holds(pass.when, frame) || std::holds_alternative<std::monostate>(pass.stage)) continue;
        const auto t0 = Clock::now();
        std::visit([&](const auto& stage) { Run(stage, stored, output); }, pass.stage);
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        if (!timings_.empty() && timings_.back().pass == pass.referenceTimer)
            timings_.back().ms += ms;
        else
            timings_.push_back({pass.referenceTimer, ms});
    }
    prevGeometry_.CopyFrom(stored);  // the normals as stored
    hasPrev_ = true;
    hasFrame_ = true;
    parity_ ^= 1;
}

void SvgfFamilyReferenceDenoiser::Run(const ReprojectStage& s, const FrameInputs& in, Plane<vec3>&) {
    const SvgfParams& p = params_.svgf;
    const bool combined = p.filterCombined;
    const size_t cur = SideIndex(HistorySide::This, parity_), prev = SideIndex(HistorySide::Previous, parity_);
    FOVRT_CHECK(!s.outputs.empty() && s.twoHistory == twoHistoryLayout_);
    // The options are the shader's mode bits, which the plan set from the variant's mechanisms.
    const bool writeColor = s.outputs.front().history.has_value();
    auto has = [&](uint32_t flag) { return (s.flags & flag) != 0; };
    if (!s.twoHistory) {
        FOVRT_CHECK(writeColor == has(SVGF_REPROJECT_FLAG_WRITE_COLOR) &&
                    combined == has(SVGF_REPROJECT_FLAG_COMBINED));
        SvgfReprojectOptions opt;
        opt.alphaColor = p.alphaColor;
        opt.alphaMoments = p.alphaMoments;
        opt.weighted = has(SVGF_REPROJECT_FLAG_WEIGHTED);
        opt.zeroSamples = has(SVGF_REPROJECT_FLAG_ZERO_SAMPLES);
        opt.writeColorHistory = writeColor;
        opt.precision = params_.precision;
        for (const StagePlane& o : s.outputs) {
            const size_t c = ChannelIndex(o.channel);
            const Plane<vec3>& color = combined || c == 0 ? in.direct : in.indirect;
            SvgfReprojectRef(color, combined ? &in.indirect : nullptr, in, prevGeometry_.View(), svgf_[prev][c],
                             svgf_[cur][c], Illum(o.out), opt, stats_);
            StoreIllum(o.out);
        }
        return;
    }
    // Both channels and histories in one call: it writes illumination planes 0 of I_u and I_w.
    for (const StagePlane& o : s.outputs)
        FOVRT_CHECK(o.out.kind == PlaneKind::Illum0 || o.out.kind == PlaneKind::WIllum0);
    FOVRT_CHECK(writeColor == has(TH_REPROJECT_FLAG_WRITE_COLOR) && combined == has(TH_REPROJECT_FLAG_COMBINED));
    TwoHistoryReprojectOptions ro;
    ro.alpha = p.alphaColor;
    ro.alphaMoments = p.alphaMoments;
    ro.gradientBeta = params_.twoHistory.gradientBeta;
    ro.twoHistory = has(TH_REPROJECT_FLAG_TWO_HISTORY);
    ro.zeroSamples = has(TH_REPROJECT_FLAG_ZERO_SAMPLES);
    ro.gradient = has(TH_REPROJECT_FLAG_GRADIENT);
    ro.writeColorHistory = writeColor;
    ro.antilag = has(TH_REPROJECT_FLAG_ANTILAG);
    ro.antilagPower = params_.asvgf.antilagPower;
    ro.suppressFireflies = has(TH_REPROJECT_FLAG_FIREFLY);
    ro.fireflySigma = params_.twoHistory.fireflySigma;
    ro.precision = params_.precision;
    ro.window = window_;
    ro.prevWindow = prevWindow_;
    const std::array<const Plane<vec3>*, 2> colors = {&in.direct, &in.indirect};
    TwoHistoryReprojectRef(colors, int(channels_.size()), combined ? &in.indirect : nullptr, in, prevGeometry_.View(),
                           hasPrev_, state_[prev], state_[cur], has(TH_REPROJECT_FLAG_ALPHA_MAP) ? &alpha_ : nullptr,
                           illum_[IllumIndex(PlaneKind::Illum0)], illum_[IllumIndex(PlaneKind::WIllum0)], ro, stats_);
    for (const StagePlane& o : s.outputs) StoreIllum(o.out);
}

void SvgfFamilyReferenceDenoiser::Run(const FilterMomentsStage& s, const FrameInputs& in, Plane<vec3>&) {
    const int parity = parity_;
    for (const StagePlane& p : s.planes) {
        const Plane<float>* length = ScalarPlane({{PlaneKind::Length, p.channel}, HistorySide::This}, parity);
        SvgfFilterMomentsRef(Illum(p.in), GeometryOf(in), in.depthGradient, Moments(p.channel), *length, Illum(p.out),
                             params_.svgf);
        StoreIllum(p.out);
    }
}

void SvgfFamilyReferenceDenoiser::Run(const AtrousStage& s, const FrameInputs& in, Plane<vec3>&) {
    for (const StagePlane& p : s.planes) {
        const bool windowed = p.history && IsWindowed(p.history->id.kind);
        SvgfAtrousRef(Illum(p.in), GeometryOf(in), in.depthGradient, s.iteration, Illum(p.out),
                      p.history ? &ColorHistory(*p.history) : nullptr, params_.svgf, params_.precision,
                      windowed ? window_ : HistoryWindow{});
        StoreIllum(p.out);
    }
}

void SvgfFamilyReferenceDenoiser::Run(const BlendStage& s, const FrameInputs&, Plane<vec3>&) {
    const TwoHistoryState& st = state_[SideIndex(HistorySide::This, parity_)];
    const Plane<float>& q = *ScalarPlane({s.q, HistorySide::None}, parity_);
    for (const StagePlane& p : s.planes) {  // in place on I_u
        TwoHistoryBlendRef(Illum(p.out), Illum(p.in), st.wu, st.ww, st.powerSums, q, blendScratch_,
                           {s.clamp, params_.twoHistory.clampSigma},
                           s.choice ? ScalarPlane(*s.choice, parity_) : nullptr, window_);
        std::swap(Illum(p.out), blendScratch_);
        StoreIllum(p.out);
    }
}

void SvgfFamilyReferenceDenoiser::Run(const EmaGradientStage& s, const FrameInputs& in, Plane<vec3>&) {
    // The stage reads every channel's (I_u, Var) after the variance estimate, as one array.
    for (const PlaneId& id : s.illumination) FOVRT_CHECK(id.kind == PlaneKind::Illum1);
    TwoHistoryGradientRef(state_[SideIndex(HistorySide::This, parity_)].gradient, illum_[IllumIndex(PlaneKind::Illum1)],
                          int(channels_.size()), in, params_.svgf, params_.twoHistory.qScale, q_);
}

void SvgfFamilyReferenceDenoiser::Run(const ModulateStage& s, const FrameInputs& in, Plane<vec3>& output) {
    SvgfModulateRef(Illum(s.illumination.front()), s.illumination.size() > 1 ? &Illum(s.illumination[1]) : nullptr,
                    in.Modulation(), in.emission, output);
}

void SvgfFamilyReferenceDenoiser::Run(const AsvgfGradientStage& s, const FrameInputs& in, Plane<vec3>&) {
    AsvgfScatterGradientsRef(in, Gradient(s.scattered), strataGuide_);
    for (size_t i = 0; i < s.iterations.size(); ++i)
        AsvgfGradientAtrousRef(Gradient(s.iterations[i].in), strataGuide_, int(i), Gradient(s.iterations[i].out),
                               params_.svgf);
}

void SvgfFamilyReferenceDenoiser::Run(const AsvgfAlphaStage& s, const FrameInputs& in, Plane<vec3>&) {
    reconstructed_ = s.reconstructed;
    AsvgfAlphaRef(Gradient(s.reconstructed), in.width(), in.height(), params_.asvgf.alpha, alpha_, lambda_,
                  s.antilag ? std::optional(params_.asvgf.antilagGain) : std::nullopt);
}

void SvgfFamilyReferenceDenoiser::Run(const ChoiceStage&, const FrameInputs& in, Plane<vec3>&) {
    const size_t cur = SideIndex(HistorySide::This, parity_), prev = SideIndex(HistorySide::Previous, parity_);
    const TwoHistoryState& st = state_[cur];
    TwoHistoryChoiceRef(in, prevGeometry_.View(), hasPrev_, choice_[prev], st.wu, st.ww, st.powerSums,
                        params_.twoHistory, params_.precision, choice_[cur], window_);
}

void SvgfFamilyReferenceDenoiser::Run(const StabilizeStage& s, const FrameInputs& in, Plane<vec3>&) {
    const size_t cur = SideIndex(HistorySide::This, parity_), prev = SideIndex(HistorySide::Previous, parity_);
    const Plane<float>& wu = *ScalarPlane({{PlaneKind::Length, channels_.front()}, HistorySide::This}, parity_);
    const Plane<float>* q = s.q ? ScalarPlane({*s.q, HistorySide::None}, parity_) : nullptr;
    for (const StagePlane& p : s.planes) {
        const size_t c = ChannelIndex(p.channel);
        TwoHistoryStabilizeRef(Illum(p.in), in, prevGeometry_.View(), hasPrev_, stable_[prev][c], wu,
                               params_.twoHistoryStable, params_.precision, stable_[cur][c], Illum(p.out), q);
        StoreIllum(p.out);
    }
}

const Plane<float>& SvgfFamilyReferenceDenoiser::StableLuminance(size_t channel) const {
    return stable_[SideIndex(HistorySide::This, parity_ ^ 1)][channel];
}

size_t SvgfFamilyReferenceDenoiser::ChannelIndex(Channel channel) const {
    for (size_t c = 0; c < channels_.size(); ++c)
        if (channels_[c] == channel) return c;
    Fail("{}: channel '{}' is not filtered", Name(), ChannelName(channel));
}

size_t SvgfFamilyReferenceDenoiser::SideIndex(HistorySide side, int parity) const {
    return SideOf(side, parity) == BufferSide::A ? 0 : 1;
}

Plane<vec4>& SvgfFamilyReferenceDenoiser::Illum(const PlaneId& id) {
    return illum_[IllumIndex(id.kind)][ChannelIndex(id.channel)];
}
const Plane<vec4>& SvgfFamilyReferenceDenoiser::Illum(const PlaneId& id) const {
    return illum_[IllumIndex(id.kind)][ChannelIndex(id.channel)];
}

const FrameInputs& SvgfFamilyReferenceDenoiser::StoredInputs(const FrameInputs& in) {
    if (params_.precision == Precision::Fp32) return in;
    storedInputs_ = in;
    for (Plane<vec3>* rgb : {&storedInputs_.direct, &storedInputs_.indirect, &storedInputs_.albedo, &storedInputs_.fbeta,
                             &storedInputs_.emission})
        for (size_t i = 0; i < rgb->size(); ++i)
            for (int c = 0; c < 3; ++c) (*rgb)[i][c] = QuantizeInput((*rgb)[i][c]);
    for (size_t i = 0; i < storedInputs_.normal.size(); ++i) storedInputs_.normal[i] = QuantizeNormal(storedInputs_.normal[i]);
    if (StoresObjectIdsInDepth(params_.precision))
        for (size_t i = 0; i < storedInputs_.linearDepth.size(); ++i) {
            const uint32_t code = DepthIdCode(storedInputs_.linearDepth[i], storedInputs_.objectId[i]);
            storedInputs_.linearDepth[i] = DepthOfCode(code);
            storedInputs_.objectId[i] = ObjectIdOfCode(code);
        }
    return storedInputs_;
}

void SvgfFamilyReferenceDenoiser::StoreIllum(const PlaneId& id) {
    if (params_.precision == Precision::Fp32) return;
    Plane<vec4>& plane = Illum(id);
    for (size_t i = 0; i < plane.size(); ++i) plane[i] = QuantizeHistory(plane[i], params_.precision);
}

Plane<vec3>& SvgfFamilyReferenceDenoiser::ColorHistory(const PlaneRef& ref) {
    const size_t side = SideIndex(ref.side, parity_), c = ChannelIndex(ref.id.channel);
    FOVRT_CHECK(ref.id.kind == PlaneKind::Color || (ref.id.kind == PlaneKind::WColor && twoHistoryLayout_));
    if (!twoHistoryLayout_) return svgf_[side][c].color;
    return ref.id.kind == PlaneKind::Color ? state_[side].iu[c] : state_[side].iw[c];
}

const Plane<vec2>& SvgfFamilyReferenceDenoiser::Moments(Channel channel) const {
    const size_t side = SideIndex(HistorySide::This, parity_), c = ChannelIndex(channel);
    return twoHistoryLayout_ ? state_[side].moments[c] : svgf_[side][c].moments;
}

const Plane<float>* SvgfFamilyReferenceDenoiser::ScalarPlane(const PlaneRef& ref, int parity) const {
    const size_t side = ref.side == HistorySide::None ? 0 : SideIndex(ref.side, parity);
    switch (ref.id.kind) {
        case PlaneKind::Length:  // two-history: W_u, shared by the channels
            return twoHistoryLayout_ ? &state_[side].wu : &svgf_[side][ChannelIndex(ref.id.channel)].length;
        case PlaneKind::Weight: return twoHistoryLayout_ ? nullptr : &svgf_[side][ChannelIndex(ref.id.channel)].weight;
        case PlaneKind::WWeight: return twoHistoryLayout_ ? &state_[side].ww : nullptr;
        case PlaneKind::Q: return &q_;
        case PlaneKind::AsvgfAlpha: return &alpha_;
        case PlaneKind::AsvgfLambda: return &lambda_;
        case PlaneKind::StableLum: {  // allocated where the plan names it
            const Plane<float>& stable = stable_[side][ChannelIndex(ref.id.channel)];
            return stable.empty() ? nullptr : &stable;
        }
        case PlaneKind::Choice: return choice_[side].empty() ? nullptr : &choice_[side];
        default: return nullptr;
    }
}

Plane<vec2>& SvgfFamilyReferenceDenoiser::Gradient(const PlaneId& id) { return gradient_[GradientIndex(id.kind)]; }
const Plane<vec2>& SvgfFamilyReferenceDenoiser::Gradient(const PlaneId& id) const {
    return gradient_[GradientIndex(id.kind)];
}

const SvgfHistory& SvgfFamilyReferenceDenoiser::CurrentHistory(size_t channel) const {
    FOVRT_CHECK(!twoHistoryLayout_);
    return svgf_[SideIndex(HistorySide::This, parity_ ^ 1)][channel];
}

const TwoHistoryState& SvgfFamilyReferenceDenoiser::CurrentState() const {
    FOVRT_CHECK(twoHistoryLayout_);
    return state_[SideIndex(HistorySide::This, parity_ ^ 1)];
}

const Plane<vec4>& SvgfFamilyReferenceDenoiser::Filtered(size_t channel) const {
    for (const PlannedPass& pass : plan_.passes)
        if (const auto* m = std::get_if<ModulateStage>(&pass.stage)) return Illum(m->illumination[channel]);
    Fail("{}: the plan has no modulation", Name());
}

const Plane<float>& SvgfFamilyReferenceDenoiser::Q() const {
    return *ScalarPlane({BlendQPlane(variant_), HistorySide::None}, parity_ ^ 1);
}

const Plane<vec2>& SvgfFamilyReferenceDenoiser::ReconstructedGradient() const { return Gradient(reconstructed_); }

bool SvgfFamilyReferenceDenoiser::ReadDebugPlane(DebugViewId view, Plane<float>& out) {
    if (!hasFrame_) return false;
    const int lastParity = parity_ ^ 1;
    const std::optional<PlaneRef> ref = DebugViewPlane(variant_, params_, view);
    if (view == DebugViewId::P && !ref) {  // not stored: the blend evaluates it from the state, as here
        if (!twoHistoryLayout_ || CurrentState().ww.empty()) return false;  // no weighted history
        const TwoHistoryState& st = CurrentState();
        // Outside the window the blend keeps I_u: p = 1.
        out = WindowOverImage(width_, height_, window_, 1.0f, [&](size_t j) {
            const ivec2 p = window_.ImagePixel(j);
            return TwoHistoryOptimalBlend(StoredTwoHistoryWeights(st.wu(p.x, p.y), st.ww[j], st.powerSums[j]));
        });
        return true;
    }
    if (ref && DebugViewComponents(view) > 1) {  // a colour history or the moments, in the state
        if (!twoHistoryLayout_) return false;
        // The state's planes hold their components interleaved, as the Vulkan buffers do.
        const TwoHistoryState& st = CurrentState();
        const size_t c = ChannelIndex(ref->id.channel);
        const float* values = ref->id.kind == PlaneKind::Color    ? &st.iu[c][0].x
                              : ref->id.kind == PlaneKind::WColor ? &st.iw[c][0].x
                                                                  : &st.moments[c][0].x;
        const size_t components = size_t(DebugViewComponents(view));
        const HistoryWindow held = IsWindowed(ref->id.kind) ? window_ : HistoryWindow::Whole(width_, height_);
        out = WindowOverImage(width_, height_, held, 0.0f,
                              [&](size_t j) { return ReduceDebugPixel(view, values + components * j); });
        return true;
    }
    const Plane<float>* plane = ref ? ScalarPlane(*ref, lastParity) : nullptr;
    if (!plane || plane->empty()) return false;
    if (IsWindowed(ref->id.kind)) {  // W_w: 0 outside its window
        out = WindowOverImage(width_, height_, window_, 0.0f, [&](size_t j) { return (*plane)[j]; });
        return true;
    }
    out = *plane;
    return true;
}

}  // namespace fovrt
