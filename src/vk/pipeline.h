// ComputePipeline: one compute shader (embedded SPIR-V from the fovrt_shaders registry), its
// descriptor-set layout (N buffers at bindings 0..N−1, set 0: storage buffers, or read-only uniform
// texel buffers where `texelFormats` names a format), a push-constant range, and a
// descriptor pool from which binding sets are made once (histories are A/B pairs, so a frame
// picks one of a few prebuilt sets instead of rewriting descriptors).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/allocator.h"

namespace fovrt {

class VulkanContext;

class ComputePipeline {
public:
    ComputePipeline() = default;
    // `shaderName` as in ShaderCode(); `bindings` storage buffers; `pushBytes` of push constants;
    // `maxSets` descriptor sets may be allocated from this pipeline. `texelFormats` (empty, or one
    // per binding): VK_FORMAT_UNDEFINED = storage buffer, else a uniform texel buffer (GLSL
    // samplerBuffer) viewing the whole buffer with that format. `specialization`: the value of the
    // int specialization constant with constant_id i is specialization[i] (ids a shader does not
    // declare are ignored, as Vulkan specifies).
    ComputePipeline(VulkanContext& context, const std::string& shaderName, uint32_t bindings,
                    uint32_t pushBytes, uint32_t maxSets = 16, std::span<const VkFormat> texelFormats = {},
                    std::span<const int32_t> specialization = {});
    ComputePipeline(ComputePipeline&& other) noexcept { *this = std::move(other); }
    ComputePipeline& operator=(ComputePipeline&& other) noexcept;
    ComputePipeline(const ComputePipeline&) = delete;
    ComputePipeline& operator=(const ComputePipeline&) = delete;
    ~ComputePipeline();

    // A descriptor set binding buffers[i] at binding i (all `bindings` must be given).
    VkDescriptorSet MakeSet(std::span<const Buffer* const> buffers);
    // Frees every set made so far (before rebuilding them after a resize).
    void ResetSets();

    VkPipeline handle() const { return pipeline_; }
    VkPipelineLayout layout() const { return layout_; }
    uint32_t pushBytes() const { return pushBytes_; }
    const std::string& name() const { return name_; }

private:
    void Destroy();
    VkDevice device_ = VK_NULL_HANDLE;
    VkShaderModule module_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    uint32_t bindings_ = 0;
    uint32_t pushBytes_ = 0;
    std::vector<VkFormat> texelFormats_;  // per binding; UNDEFINED = storage buffer
    std::vector<VkBufferView> views_;     // made by MakeSet, freed by ResetSets
    void DestroyViews();
    std::string name_;
};

}  // namespace fovrt
