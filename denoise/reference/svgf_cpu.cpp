#include "denoise/reference/svgf_cpu.h"

#include "core/error.h"
#include "denoise/schedule.h"
#include "denoise/variants.h"

namespace fovrt {

namespace {
class PassClock {
public:
    explicit PassClock(std::vector<PassTiming>& out) : out_(out) {}
    void Lap(const std::string& pass) {
        auto now = std::chrono::steady_clock::now();
        out_.push_back({pass, std::chrono::duration<double, std::milli>(now - last_).count()});
        last_ = now;
    }

private:
    std::vector<PassTiming>& out_;
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};
}  // namespace

SvgfReferenceDenoiser::SvgfReferenceDenoiser(std::string name, const DenoiserParams& params)
    : name_(std::move(name)), params_(params) {
    ValidateDenoiserParamRanges(params_);
}

void SvgfReferenceDenoiser::Allocate(int width, int height) {
    width_ = width;
    height_ = height;
    channels_.assign(SvgfChannels(params_.svgf).size(), Channel{});
    for (Channel& ch : channels_)
        for (auto& h : ch.hist) h.Allocate(width, height, params_.svgf.weightBySampleCount);
    prevGeometry_.Allocate(width, height);
    parity_ = 0;
    hasFrame_ = false;
}

void SvgfReferenceDenoiser::Reset() {
    if (width_ > 0) Allocate(width_, height_);
}

void SvgfReferenceDenoiser::SetParams(const DenoiserParams& params) {
    ValidateDenoiserParamRanges(params);
    params_ = params;
    Reset();
}

void SvgfReferenceDenoiser::Denoise(const FrameInputs& in, Plane<vec3>& output) {
    if (in.width() != width_ || in.height() != height_)
        Allocate(in.width(), in.height());
    else if (in.cameraCut)
        Reset();
    timings_.clear();
    PassClock clock(timings_);
    const SvgfParams& p = params_.svgf;
    const int iterations = p.atrousIterations;
    const int feedbackIteration = FeedbackIteration(p, false);
    const bool atrousFeedback = feedbackIteration > 0;
    SvgfReprojectOptions opt;
    opt.alphaColor = p.alphaColor;
    opt.alphaMoments = p.alphaMoments;
    opt.weighted = p.weightBySampleCount;
    opt.writeColorHistory = !atrousFeedback;
    opt.precision = params_.precision;
    const SvgfGeometry cur = GeometryOf(in);
    for (size_t c = 0; c < channels_.size(); ++c) {
        Channel& ch = channels_[c];
        const bool combined = p.filterCombined;
        const Plane<vec3>& color = combined || c == 0 ? in.direct : in.indirect;
        SvgfReprojectRef(color, combined ? &in.indirect : nullptr, in, prevGeometry_.View(),
                         ch.hist[parity_ ^ 1], ch.hist[parity_], ch.illum[0], opt, stats_);
    }
    clock.Lap("reproject");
    for (Channel& ch : channels_)
        SvgfFilterMomentsRef(ch.illum[0], cur, in.depthGradient, ch.hist[parity_].moments,
                             ch.hist[parity_].length, ch.illum[1], p);
    clock.Lap("filter_moments");
    for (int i = 0; i < iterations; ++i) {
        for (Channel& ch : channels_) {
            Plane<vec3>* feedback = atrousFeedback && i + 1 == feedbackIteration ? &ch.hist[parity_].color : nullptr;
            SvgfAtrousRef(ch.illum[(i + 1) & 1], cur, in.depthGradient, i, ch.illum[i & 1], feedback, p,
                          params_.precision);
        }
        clock.Lap(fmt::format("atrous{}", i));
    }
    const int last = FilteredIlluminationPlane(iterations);
    for (Channel& ch : channels_) ch.filtered = ch.illum[last];
    SvgfModulateRef(channels_[0].filtered, channels_.size() > 1 ? &channels_[1].filtered : nullptr, in.Modulation(),
                    in.emission, output);
    clock.Lap("modulate");
    prevGeometry_.CopyFrom(in);
    parity_ ^= 1;
    hasFrame_ = true;
}

bool SvgfReferenceDenoiser::ReadDebugPlane(DebugViewId view, Plane<float>& out) {
    if (!hasFrame_) return false;
    const SvgfHistory& history = CurrentHistory(0);  // every channel has the same length
    switch (view) {
        case DebugViewId::HistoryLength:
            out = history.length;
            return true;
        case DebugViewId::HistorySamples:  // W of svgf-weighted (the channels share it too)
            if (history.weight.empty()) return false;
            out = history.weight;
            return true;
        case DebugViewId::Alpha:
        case DebugViewId::Lambda:
        case DebugViewId::P:
        case DebugViewId::Q:
            return false;  // views of the two-history family
    }
    return false;
}

}  // namespace fovrt
