// The recurrent denoising autoencoder on Vulkan compute (Chaitanya et al. 2017, §4):
// shaders/rae_conv.comp (one dispatch per 3×3 conv; concatenation and 2×2 upsampling by addressing)
// and rae_pool.comp (2×2 max-pool), all tensors in one activation buffer laid out by
// RaeTensorLayout, the hidden state an A/B pair per level selected by frame parity. The features
// and the remodulation run on the host (the C++ reference's RaeFeatures / RaeRemodulate: O(pixels),
// no network work). Held to the C++ reference (RaeForward) by tests/denoise_rae_vulkan_test.cpp,
// layer by layer and end to end. Precision::Fp16 stores activations (not weights, not the
// accumulation) as float16.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "denoise/denoiser.h"
#include "denoise/rae_weights.h"
#include "vk/context.h"
#include "vk/pipeline.h"
#include "vk/recorder.h"

namespace fovrt {

struct Tensor;

class RaeVulkanDenoiser : public Denoiser {
public:
    RaeVulkanDenoiser(std::string name, std::shared_ptr<VulkanContext> context, const DenoiserParams& params);
    ~RaeVulkanDenoiser() override;
    std::string Name() const override { return name_; }
    std::string Backend() const override { return "vulkan"; }
    void Reset() override { needsClear_ = true; }
    void Denoise(const FrameInputs& inputs, Plane<vec3>& output) override;
    std::vector<PassTiming> LastTimings() const override { return timings_; }
    DenoiseStats Stats() const override { return {}; }

    // The network alone (tests): `input` (padded, colour^γ) → `out` (3 channels, γ space), the
    // hidden state carried like Denoise() carries it.
    void Forward(const Tensor& input, Tensor& out);
    // A tensor of the layout after the last Forward()/Denoise() (tests: layer by layer).
    // "rae.hidden<l>" names the side written last.
    void ReadTensor(const std::string& name, Tensor& out);
    const RaeWeights& Weights() const { return *weights_; }

private:
    bool ReadDebugPlane(DebugViewId, Plane<float>&) override { return false; }
    void Allocate(int paddedWidth, int paddedHeight);
    void RecordNetwork(CommandRecorder& rec);
    void Conv(CommandRecorder& rec, int conv, const RaeTensorSlot& a, const RaeTensorSlot* b, bool upsampleA,
              const RaeTensorSlot& dst, bool leaky);
    void Pool(CommandRecorder& rec, const RaeTensorSlot& src, const RaeTensorSlot& dst);
    const RaeTensorSlot& Slot(const std::string& name) const { return FindRaeSlot(layout_, name); }
    std::string Hidden(int level, bool written) const;

    std::string name_;
    std::shared_ptr<VulkanContext> context_;
    std::shared_ptr<const RaeWeights> weights_;
    DenoiserParams params_;
    bool fp16_ = false;
    std::vector<uint32_t> weightOffsets_, biasOffsets_;  // per conv, in floats of the weight buffer
    int paddedWidth_ = 0, paddedHeight_ = 0;
    std::vector<RaeTensorSlot> layout_;
    Buffer activations_, weightBuffer_, staging_;
    ComputePipeline conv_, pool_;
    VkDescriptorSet convSet_ = VK_NULL_HANDLE, poolSet_ = VK_NULL_HANDLE;
    CommandSlot slot_;
    TimestampPool timestamps_;
    int parity_ = 0;  // hidden side written this frame: 0 → A, 1 → B
    bool needsClear_ = true;
    std::vector<PassTiming> timings_;
    std::vector<uint16_t> half_;  // fp16 activations: the input before its upload, the output after its download
};

}  // namespace fovrt
