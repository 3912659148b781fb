// SVGF on Vulkan compute: shaders/svgf_*.comp composed as in the paper, one dispatch per stage
// and channel except reprojection and à-trous (both channels in one dispatch: svgf_*_pair), GPU
// timestamps per pass. Buffers are allocated by iterating PlanSvgfMemory(), so `fovrt memory`
// lists exactly what is allocated. Histories (and the geometry of the previous frame) are A/B
// pairs selected by a parity bit; descriptor sets are built once per size.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "denoise/denoiser.h"
#include "denoise/vulkan/svgf_atrous_vk.h"
#include "denoise/vulkan/vk_denoiser_buffers.h"
#include "vk/context.h"
#include "vk/pipeline.h"
#include "vk/recorder.h"

namespace fovrt {

class SvgfVulkanDenoiser : public Denoiser {
public:
    // `context` is shared (e.g. by both eyes); it must outlive nothing but this object.
    SvgfVulkanDenoiser(std::string name, std::shared_ptr<VulkanContext> context, const DenoiserParams& params);
    ~SvgfVulkanDenoiser() override;
    std::string Name() const override { return name_; }
    std::string Backend() const override { return "vulkan"; }
    void Reset() override;
    // New parameters: drops every history (through the same path as Reset()) and rebuilds the
    // pipelines and buffers on the next Denoise().
    void SetParams(const DenoiserParams& params);
    void Denoise(const FrameInputs& inputs, Plane<vec3>& output) override;
    std::vector<PassTiming> LastTimings() const override { return timings_; }
    DenoiseStats Stats() const override { return stats_; }

    VulkanContext& context() { return *context_; }
    // Downloads a buffer of the plan by name (tests: history contents after Denoise()).
    std::vector<uint8_t> ReadBuffer(const std::string& name);
    // Name suffix of the history side written by the last Denoise() ("A" or "B").
    std::string LastWrittenSide() const { return parity_ ? "A" : "B"; }

private:
    bool ReadDebugPlane(DebugViewId view, Plane<float>& out) override;
    void CreatePipelines();
    void Allocate(int width, int height);
    void BuildSets();
    Buffer& Buf(const std::string& name);

    std::string name_;
    std::shared_ptr<VulkanContext> context_;
    DenoiserParams params_;
    std::vector<std::string> channels_;
    int width_ = 0, height_ = 0;
    int parity_ = 0;          // history side written this frame: 0 → A, 1 → B
    bool needsClear_ = true;  // histories must be cleared before the next frame
    bool hasFrame_ = false;   // a Denoise() since construction, Reset() or a resize (debug views)
    DenoiserBuffers buffers_{"svgf"};
    SvgfStagePipelines stages_;  // guide, moments, à-trous, modulate (svgf_atrous_vk.h)
    ReprojectionPipelines reproject_;  // main + box-fallback passes
    std::array<VkDescriptorSet, 2> guideSets_{};  // [parity]
    // Descriptor sets: [channel][parity]; reproject: [parity] and atrous: [parity][pingpong], both
    // channels in one set.
    std::vector<std::array<VkDescriptorSet, 2>> momentsSets_, classifySets_;
    std::array<VkDescriptorSet, 2> reprojectSets_{};
    std::array<std::array<VkDescriptorSet, 2>, 2> atrousSets_{};
    VkDescriptorSet modulateSet_ = VK_NULL_HANDLE;
    TimestampPool timestamps_;
    CommandSlot commands_;  // reused by every Denoise()
    std::vector<PassTiming> timings_;
    DenoiseStats stats_;
};

}  // namespace fovrt
