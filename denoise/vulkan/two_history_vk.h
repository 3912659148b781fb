// Two-history SVGF, A-SVGF and two-history-asvgf on Vulkan compute: the new stages
// (shaders/two_history_*.comp, shaders/asvgf_*.comp) composed with SVGF's own shaders
// (svgf_filter_moments, svgf_atrous, svgf_modulate), one dispatch per stage, GPU timestamps per
// pass. Buffers are allocated by iterating PlanDenoiserMemory(), so `fovrt memory` lists
// exactly what is allocated. Same maths as TwoHistoryReferenceDenoiser (two_history_ref.h).
#pragma once

#include <array>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "denoise/denoiser.h"
#include "denoise/vulkan/svgf_atrous_vk.h"
#include "denoise/vulkan/vk_denoiser_buffers.h"
#include "denoise/gradient_strata.h"
#include "denoise/params.h"
#include "denoise/variants.h"
#include "vk/context.h"
#include "vk/pipeline.h"
#include "vk/recorder.h"

namespace fovrt {

class TwoHistoryVulkanDenoiser : public Denoiser {
  public:
    TwoHistoryVulkanDenoiser(const DenoiserVariant& variant, std::shared_ptr<VulkanContext> context,
                             const DenoiserParams& params);
    ~TwoHistoryVulkanDenoiser() override;
    std::string Name() const override { return std::string(variant_.name); }
    std::string Backend() const override { return "vulkan"; }
    void Reset() override {
        needsClear_ = true;
        hasFrame_ = false;
    }
    void Denoise(const FrameInputs& inputs, Plane<vec3>& output) override;
    std::vector<PassTiming> LastTimings() const override { return timings_; }
    DenoiseStats Stats() const override { return stats_; }

    VulkanContext& context() { return *context_; }
    // Downloads a buffer of the plan by name (tests: histories and scratch after Denoise()).
    std::vector<uint8_t> ReadBuffer(const std::string& name);
    // Name suffix of the history side written by the last Denoise() ("A" or "B").
    std::string LastWrittenSide() const { return parity_ ? "A" : "B"; }

  private:
    bool ReadDebugPlane(DebugViewId view, Plane<float>& out) override;
    // The buffer of q the blend reads: the EMA gradient's "q", or A-SVGF's λ̂ (two-history-asvgf).
    std::string QBuffer() const { return variant_.emaGradient ? "q" : "asvgf.lambda"; }
    void Allocate(int width, int height);
    void BuildSets();
    Buffer& Buf(const std::string& name);

    const DenoiserVariant& variant_;  // a row of DenoiserVariants(): which passes run
    std::shared_ptr<VulkanContext> context_;
    DenoiserParams params_;
    bool two_ = false, asvgf_ = false;
    std::vector<std::string> channels_;
    int width_ = 0, height_ = 0;
    ivec2 grid_{0};
    int parity_ = 0;
    bool needsClear_ = true;
    bool hasPrev_ = false;
    bool hasFrame_ = false;  // a Denoise() since construction, Reset() or a resize (debug views)
    DenoiserBuffers buffers_;
    SvgfStagePipelines stages_;  // guide, moments, à-trous, modulate (svgf_atrous_vk.h)
    ReprojectionPipelines reproject_;  // main + box-fallback passes
    ComputePipeline gradient_, blend_;
    std::array<VkDescriptorSet, 2> guideSets_{};  // [parity]
    ComputePipeline claim_, gather_, stratumSigma_, gradAtrous_, alpha_;
    std::array<VkDescriptorSet, 2> gradientSets_{};
    std::array<VkDescriptorSet, 2> reprojectSets_{};  // both channels (pair) or the combined one
    std::vector<std::array<VkDescriptorSet, 2>> classifySets_, momentsU_, momentsW_, blendSets_;
    // À-trous on all channels' I_u in one dispatch: [parity][pingpong]. Iteration 0 of the
    // two-history variants also filters I_w: [parity] → the dispatches of that iteration (separate
    // channels: the I_u pair and the I_w pair; combined: one I_u + I_w pair on atrousPair_).
    ComputePipeline atrousPair_;  // step-1 pair variant (iteration 0, combined two-history)
    std::array<std::array<VkDescriptorSet, 2>, 2> atrousU_{};
    std::array<std::vector<std::pair<const ComputePipeline*, VkDescriptorSet>>, 2> atrousFirst_;
    VkDescriptorSet claimSet_ = VK_NULL_HANDLE, sigmaSet_ = VK_NULL_HANDLE;
    std::array<VkDescriptorSet, 2> gatherSets_{};      // [parity]: this frame's geometry side
    std::array<VkDescriptorSet, 2> gradAtrousSets_{};  // [pingpong]
    VkDescriptorSet alphaSet_ = VK_NULL_HANDLE, modulateSet_ = VK_NULL_HANDLE;
    TimestampPool timestamps_;
    CommandSlot commands_;  // reused by every Denoise()
    std::vector<PassTiming> timings_;
    DenoiseStats stats_;
};

}  // namespace fovrt
