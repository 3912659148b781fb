#include "vk/pipeline.h"

#include <utility>

#include "core/error.h"
#include "shaders/shader_registry.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace fovrt {

namespace {
VkDescriptorType TypeOf(VkFormat texelFormat) {
    return texelFormat == VK_FORMAT_UNDEFINED ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                                              : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
}
}  // namespace

ComputePipeline::ComputePipeline(VulkanContext& context, const std::string& shaderName,
                                 uint32_t bindings, uint32_t pushBytes, uint32_t maxSets,
                                 std::span<const VkFormat> texelFormats,
                                 std::span<const int32_t> specialization)
    : device_(context.device()), bindings_(bindings), pushBytes_(pushBytes), name_(shaderName) {
    if (!texelFormats.empty() && texelFormats.size() != bindings)
        Fail("pipeline {}: {} texel formats given for {} bindings", shaderName, texelFormats.size(), bindings);
    texelFormats_.assign(bindings, VK_FORMAT_UNDEFINED);
    for (uint32_t b = 0; b < texelFormats.size(); ++b) {
        texelFormats_[b] = texelFormats[b];
        if (texelFormats[b] == VK_FORMAT_UNDEFINED) continue;
        VkFormatProperties props;
        vkGetPhysicalDeviceFormatProperties(context.physicalDevice(), texelFormats[b], &props);
        if (!(props.bufferFeatures & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT))
            Fail("pipeline {}: Vulkan device '{}' cannot use format {} for uniform texel buffers (binding {})",
                 shaderName, context.deviceName(), int(texelFormats[b]), b);
    }
    std::span<const uint32_t> code = ShaderCode(shaderName);
    auto moduleInfo = VkInit<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    moduleInfo.codeSize = code.size_bytes();
    moduleInfo.pCode = code.data();
    FOVRT_VK(vkCreateShaderModule(device_, &moduleInfo, nullptr, &module_));

    std::vector<VkDescriptorSetLayoutBinding> layoutBindings(bindings);
    for (uint32_t b = 0; b < bindings; ++b) {
        layoutBindings[b].binding = b;
        layoutBindings[b].descriptorType = TypeOf(texelFormats_[b]);
        layoutBindings[b].descriptorCount = 1;
        layoutBindings[b].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    auto setInfo = VkInit<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    setInfo.bindingCount = bindings;
    setInfo.pBindings = layoutBindings.data();
    FOVRT_VK(vkCreateDescriptorSetLayout(device_, &setInfo, nullptr, &setLayout_));

    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes};
    auto layoutInfo = VkInit<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &setLayout_;
    layoutInfo.pushConstantRangeCount = pushBytes ? 1 : 0;
    layoutInfo.pPushConstantRanges = &range;
    FOVRT_VK(vkCreatePipelineLayout(device_, &layoutInfo, nullptr, &layout_));

    auto pipeInfo = VkInit<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    pipeInfo.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    pipeInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeInfo.stage.module = module_;
    pipeInfo.stage.pName = "main";
    std::vector<VkSpecializationMapEntry> specEntries(specialization.size());
    for (uint32_t i = 0; i < specEntries.size(); ++i)
        specEntries[i] = {i, uint32_t(i * sizeof(int32_t)), sizeof(int32_t)};
    VkSpecializationInfo specInfo{uint32_t(specEntries.size()), specEntries.data(), specialization.size_bytes(),
                                  specialization.data()};
    if (!specialization.empty()) pipeInfo.stage.pSpecializationInfo = &specInfo;
    pipeInfo.layout = layout_;
    FOVRT_VK(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &pipeInfo, nullptr, &pipeline_));

    uint32_t texels = 0;
    for (VkFormat f : texelFormats_) texels += f != VK_FORMAT_UNDEFINED ? 1u : 0u;
    VkDescriptorPoolSize poolSizes[2] = {
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, std::max(1u, bindings - texels) * maxSets},
        {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, std::max(1u, texels) * maxSets}};
    auto poolInfo = VkInit<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    poolInfo.maxSets = maxSets;
    poolInfo.poolSizeCount = 2;
    poolInfo.pPoolSizes = poolSizes;
    FOVRT_VK(vkCreateDescriptorPool(device_, &poolInfo, nullptr, &pool_));
}

ComputePipeline& ComputePipeline::operator=(ComputePipeline&& other) noexcept {
    if (this != &other) {
        Destroy();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        module_ = std::exchange(other.module_, VK_NULL_HANDLE);
        setLayout_ = std::exchange(other.setLayout_, VK_NULL_HANDLE);
        layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
        pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
        pool_ = std::exchange(other.pool_, VK_NULL_HANDLE);
        bindings_ = other.bindings_;
        pushBytes_ = other.pushBytes_;
        texelFormats_ = std::move(other.texelFormats_);
        views_ = std::move(other.views_);
        other.views_.clear();
        name_ = std::move(other.name_);
    }
    return *this;
}

ComputePipeline::~ComputePipeline() { Destroy(); }

void ComputePipeline::Destroy() {
    if (device_ == VK_NULL_HANDLE) return;
    DestroyViews();
    if (pool_) vkDestroyDescriptorPool(device_, pool_, nullptr);
    if (pipeline_) vkDestroyPipeline(device_, pipeline_, nullptr);
    if (layout_) vkDestroyPipelineLayout(device_, layout_, nullptr);
    if (setLayout_) vkDestroyDescriptorSetLayout(device_, setLayout_, nullptr);
    if (module_) vkDestroyShaderModule(device_, module_, nullptr);
    device_ = VK_NULL_HANDLE;
}

VkDescriptorSet ComputePipeline::MakeSet(std::span<const Buffer* const> buffers) {
    if (buffers.size() != bindings_)
        Fail("pipeline {}: {} buffers given for {} bindings", name_, buffers.size(), bindings_);
    auto info = VkInit<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    info.descriptorPool = pool_;
    info.descriptorSetCount = 1;
    info.pSetLayouts = &setLayout_;
    VkDescriptorSet set = VK_NULL_HANDLE;
    FOVRT_VK(vkAllocateDescriptorSets(device_, &info, &set));
    std::vector<VkDescriptorBufferInfo> infos(bindings_);
    std::vector<VkBufferView> views(bindings_, VK_NULL_HANDLE);
    std::vector<VkWriteDescriptorSet> writes(bindings_);
    for (uint32_t b = 0; b < bindings_; ++b) {
        if (!buffers[b] || !buffers[b]->valid()) Fail("pipeline {}: binding {} has no buffer", name_, b);
        infos[b] = {buffers[b]->handle(), 0, VK_WHOLE_SIZE};
        writes[b] = VkInit<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        writes[b].dstSet = set;
        writes[b].dstBinding = b;
        writes[b].descriptorCount = 1;
        writes[b].descriptorType = TypeOf(texelFormats_[b]);
        if (texelFormats_[b] == VK_FORMAT_UNDEFINED) {
            writes[b].pBufferInfo = &infos[b];
        } else {
            auto view = VkInit<VkBufferViewCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO);
            view.buffer = buffers[b]->handle();
            view.format = texelFormats_[b];
            view.offset = 0;
            view.range = VK_WHOLE_SIZE;
            FOVRT_VK(vkCreateBufferView(device_, &view, nullptr, &views[b]));
            views_.push_back(views[b]);
            writes[b].pTexelBufferView = &views[b];
        }
    }
    vkUpdateDescriptorSets(device_, bindings_, writes.data(), 0, nullptr);
    return set;
}

void ComputePipeline::ResetSets() {
    FOVRT_VK(vkResetDescriptorPool(device_, pool_, 0));
    DestroyViews();
}

void ComputePipeline::DestroyViews() {
    for (VkBufferView v : views_) vkDestroyBufferView(device_, v, nullptr);
    views_.clear();
}

}  // namespace fovrt
