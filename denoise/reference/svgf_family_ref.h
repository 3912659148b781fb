// The C++ reference of the SVGF family (svgf, svgf-weighted, asvgf, two-history,
// two-history-asvgf; Backend() == "cpu", also the fallback without a Vulkan device). It walks the
// variant's pass plan (denoise/pass_plan.h), the list the Vulkan host records, and runs each
// pass's ReferenceStage: one stage function of svgf_ref.h, two_history_ref.h or asvgf_ref.h on
// the planes the stage names (ping-pong planes, feedback targets, q). Passes with no stage
// (upload, pack_guide, download) are the host's: the reference reads FrameInputs directly.
//
// The histories keep the layout of the plan's reprojection stage: an SvgfHistory per channel
// (svgf_reproject) or one TwoHistoryState (two_history_reproject, whose W_u every channel shares).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "denoise/denoiser.h"
#include "denoise/pass_plan.h"
#include "denoise/reference/asvgf_ref.h"
#include "denoise/reference/svgf_ref.h"
#include "denoise/reference/two_history_ref.h"
#include "denoise/reference/two_history_choice_ref.h"
#include "denoise/reference/two_history_stable_ref.h"

namespace fovrt {

class SvgfFamilyReferenceDenoiser final : public Denoiser {
  public:
    SvgfFamilyReferenceDenoiser(const DenoiserVariant& variant, const DenoiserParams& params);
    std::string Name() const override { return std::string(variant_.name); }
    std::string Backend() const override { return "cpu"; }
    void Reset() override;
    // New parameters: drops every history, as Reset().
    void SetParams(const DenoiserParams& params);
    void Denoise(const FrameInputs& inputs, Plane<vec3>& output) override;
    std::vector<PassTiming> LastTimings() const override { return timings_; }
    DenoiseStats Stats() const override { return stats_; }

    // Read access for tests, after Denoise(). svgf and svgf-weighted: this frame's history of
    // channel c; the two-history family: this frame's state.
    const SvgfHistory& CurrentHistory(size_t channel) const;
    const TwoHistoryState& CurrentState() const;
    // Illumination ping-pong plane k (0, 1) of channel c: the reprojection writes plane 0, the
    // variance estimate plane 1, à-trous iteration i plane i&1; Filtered(c) is the one modulated.
    const Plane<vec4>& Illum(size_t channel, int k) const { return illum_[size_t(k)][channel]; }
    const Plane<vec4>& Filtered(size_t channel) const;
    size_t ChannelCount() const { return channels_.size(); }
    // The blend's q (two-history: the EMA gradient's; two-history-asvgf: λ̂), A-SVGF's α, λ and
    // reconstructed (δ̂, Δ̂).
    const Plane<float>& Q() const;
    const Plane<float>& Alpha() const { return alpha_; }
    const Plane<float>& Lambda() const { return lambda_; }
    const Plane<vec2>& ReconstructedGradient() const;
    // two-history-stable: this frame's stabilised luminance of channel c.
    const Plane<float>& StableLuminance(size_t channel) const;

  private:
    bool ReadDebugPlane(DebugViewId view, Plane<float>& out) override;
    void Allocate(int width, int height);

    // One stage per pass (denoise/pass_plan.h ReferenceStage).
    void Run(const std::monostate&, const FrameInputs&, Plane<vec3>&) {}
    void Run(const ReprojectStage& s, const FrameInputs& in, Plane<vec3>&);
    void Run(const FilterMomentsStage& s, const FrameInputs& in, Plane<vec3>&);
    void Run(const AtrousStage& s, const FrameInputs& in, Plane<vec3>&);
    void Run(const BlendStage& s, const FrameInputs& in, Plane<vec3>&);
    void Run(const EmaGradientStage& s, const FrameInputs& in, Plane<vec3>&);
    void Run(const ModulateStage& s, const FrameInputs& in, Plane<vec3>& output);
    void Run(const AsvgfGradientStage& s, const FrameInputs& in, Plane<vec3>&);
    void Run(const AsvgfAlphaStage& s, const FrameInputs& in, Plane<vec3>&);
    void Run(const StabilizeStage& s, const FrameInputs& in, Plane<vec3>&);
    void Run(const ChoiceStage&, const FrameInputs& in, Plane<vec3>&);

    // The planes a stage names, in this reference's storage; `parity` 0 writes histories to
    // side A (this frame's parity_ during Denoise()).
    size_t ChannelIndex(Channel channel) const;
    size_t SideIndex(HistorySide side, int parity) const;
    Plane<vec4>& Illum(const PlaneId& id);
    const Plane<vec4>& Illum(const PlaneId& id) const;
    // Rounds an illumination plane a stage wrote as the Vulkan host stores it (fp16 in fp16 mode).
    void StoreIllum(const PlaneId& id);
    // The frame's inputs as the Vulkan host uploads them: `in` itself in fp32, a copy whose colours
    // and normals are rounded by QuantizeInput and QuantizeNormal in fp16 (planes.h).
    const FrameInputs& StoredInputs(const FrameInputs& in);
    Plane<vec3>& ColorHistory(const PlaneRef& ref);
    const Plane<vec2>& Moments(Channel channel) const;  // this frame's
    const Plane<float>* ScalarPlane(const PlaneRef& ref, int parity) const;
    Plane<vec2>& Gradient(const PlaneId& id);
    const Plane<vec2>& Gradient(const PlaneId& id) const;

    const DenoiserVariant& variant_;  // a row of DenoiserVariants()
    DenoiserParams params_;           // as ParamsForVariant gives them
    DenoiserPlan plan_;               // built at the frame size
    std::vector<Channel> channels_;
    bool twoHistoryLayout_ = false;   // the plan reprojects with two_history_reproject
    int width_ = 0, height_ = 0;
    bool hasPrev_ = false;   // the histories hold a previous frame
    bool hasFrame_ = false;  // a Denoise() since construction or Reset() (debug views)
    int parity_ = 0;         // this frame's histories go to side A (0) or B (1)
    HistoryWindow window_, prevWindow_;  // the weighted history's window, this frame and the last
    SvgfGeometryPlanes prevGeometry_;
    std::array<std::vector<SvgfHistory>, 2> svgf_;  // [side][channel]: svgf_reproject's layout
    std::array<TwoHistoryState, 2> state_;          // [side]: two_history_reproject's layout
    std::array<std::array<Plane<vec4>, 2>, 4> illum_;  // [illum0, illum1, willum0, willum1][channel]
    Plane<vec4> blendScratch_;
    FrameInputs storedInputs_;  // StoredInputs' copy (fp16)
    std::array<Plane<vec2>, 2> gradient_;  // A-SVGF (δ, Δ) ping-pong per stratum
    Plane<StratumGuide> strataGuide_;
    PlaneId reconstructed_;
    Plane<float> alpha_, lambda_, q_;
    std::array<std::array<Plane<float>, 2>, 2> stable_;  // [side][channel]: L_s of two_history_stabilize
    std::array<Plane<float>, 2> choice_;                 // [side]: the held choice of two_history_choice
    std::vector<PassTiming> timings_;
    DenoiseStats stats_;
};

}  // namespace fovrt
