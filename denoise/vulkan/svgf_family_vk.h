// The Vulkan host of the SVGF family (svgf, svgf-weighted, asvgf, two-history,
// two-history-asvgf, and their +brdf/+albedo forms through denoise/demodulation.h): it records
// the variant's pass plan (denoise/pass_plan.h) as it stands, pass by pass with a GPU timer
// each, and knows no pass by name. Buffers are allocated by iterating the plan's memory plan;
// pipelines are made once per distinct PipelineKey, and a descriptor set per dispatch and history
// parity once per size, so a frame only picks prebuilt sets. Histories are A/B pairs: the frame
// with parity 0 writes side A and reads B as the previous frame. The same list runs on the C++
// reference (denoise/reference/svgf_family_ref.h), which the tests hold this host to.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "denoise/denoiser.h"
#include "denoise/pass_plan.h"
#include "denoise/vulkan/vk_denoiser_buffers.h"
#include "vk/context.h"
#include "vk/pipeline.h"
#include "vk/recorder.h"
#include "vk/transfer_ring.h"

namespace fovrt {

class SvgfFamilyVulkanDenoiser final : public Denoiser {
  public:
    // `context` is shared (e.g. by both eyes); it must outlive nothing but this object.
    SvgfFamilyVulkanDenoiser(const DenoiserVariant& variant, std::shared_ptr<VulkanContext> context,
                             const DenoiserParams& params);
    ~SvgfFamilyVulkanDenoiser() override;
    std::string Name() const override { return std::string(variant_.name); }
    std::string Backend() const override { return "vulkan"; }
    void Reset() override;
    // New parameters: drops every history (as Reset()), rebuilds plan, pipelines and buffers on
    // the next Denoise().
    void SetParams(const DenoiserParams& params);
    void Denoise(const FrameInputs& inputs, Plane<vec3>& output) override;
    std::vector<PassTiming> LastTimings() const override { return timings_; }
    DenoiseStats Stats() const override { return stats_; }

    VulkanContext& context() { return *context_; }
    // Downloads a buffer of the memory plan by its printed name, e.g. "direct.length.A" (tests:
    // histories and scratch after Denoise()).
    std::vector<uint8_t> ReadBuffer(const std::string& name);
    // Whether ReadBuffer(name) can read it: false for a transient plane whose slot a plane
    // written later in the frame reused, and for names not in the plan.
    bool Readable(const std::string& name) const { return buffers_.Readable(name); }
    // Name suffix of the history side written by the last Denoise() ("A" or "B").
    std::string LastWrittenSide() const { return parity_ ? "A" : "B"; }

  private:
    // What a command needs from the frame being recorded.
    struct Frame {
        const FrameInputs& inputs;
        FrameConditions conditions;
        uint32_t gradientSamples;
        TransferRing& transfers;            // the frame's uploads and downloads
        Plane<vec3>& output;                // where the output plane's download lands
        std::array<uint32_t, 2>& counters;  // … and the sanitising counters'
        HistoryWindow window, prevWindow;   // the weighted history's, this frame and the previous
    };
    // A planned dispatch, ready to record: its pipeline and its set per history parity.
    struct PreparedDispatch {
        const ComputePipeline* pipeline = nullptr;
        std::array<VkDescriptorSet, 2> sets{};
    };

    bool ReadDebugPlane(DebugViewId view, Plane<float>& out) override;
    // Checks `params` (ranges; fp16 storage on this device) and keeps them as the row implies.
    void Configure(const DenoiserParams& params);
    void Allocate(int width, int height);
    void PrepareDispatches();
    void Record(CommandRecorder& rec, const DispatchCommand& d, const PreparedDispatch& prepared, Frame& frame);
    void Record(CommandRecorder& rec, const Command& command, const PreparedDispatch& prepared, Frame& frame);

    const DenoiserVariant& variant_;  // a row of DenoiserVariants()
    std::shared_ptr<VulkanContext> context_;
    DenoiserParams params_;  // as ParamsForVariant gives them
    DenoiserPlan plan_;      // at the current size
    int width_ = 0, height_ = 0;
    int parity_ = 0;          // history side written this frame: 0 → A, 1 → B
    HistoryWindow window_;    // the weighted history's window of the last frame
    bool needsClear_ = true;  // histories must be cleared before the next frame
    bool hasFrame_ = false;   // a Denoise() since construction, Reset() or a resize (debug views)
    DenoiserBuffers buffers_;
    std::map<PipelineKey, ComputePipeline> pipelines_;      // one per distinct key of the plan
    std::vector<std::vector<PreparedDispatch>> prepared_;  // [pass][command]
    uint64_t preparedGeneration_ = 0;  // SharedGeneration() when prepared_ was made
    TimestampPool timestamps_;
    CommandSlot commands_;  // reused by every Denoise()
    std::vector<PassTiming> timings_;
    std::vector<uint16_t> halfInput_;  // an input converted for upload (fp16 storage: ConvertForUpload)
    DenoiseStats stats_;
};

}  // namespace fovrt
