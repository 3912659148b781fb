#include "vk/recorder.h"

#include <cstring>
#include <utility>

#include "core/check.h"
#include "core/error.h"
#include "vk/context.h"
#include "vk/pipeline.h"
#include "vk/vk_check.h"

namespace fovrt {

TimestampPool::TimestampPool(VulkanContext& context, uint32_t maxPasses) {
    if (!context.supportsTimestamps()) return;
    device_ = context.device();
    capacity_ = 2 * maxPasses;
    periodNs_ = context.timestampPeriodNs();
    auto info = VkInit<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = capacity_;
    FOVRT_VK(vkCreateQueryPool(device_, &info, nullptr, &pool_));
}

TimestampPool& TimestampPool::operator=(TimestampPool&& other) noexcept {
    if (this != &other) {
        if (pool_) vkDestroyQueryPool(device_, pool_, nullptr);
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        pool_ = std::exchange(other.pool_, VK_NULL_HANDLE);
        capacity_ = other.capacity_;
        periodNs_ = other.periodNs_;
        names_ = std::move(other.names_);
    }
    return *this;
}

TimestampPool::~TimestampPool() {
    if (pool_) vkDestroyQueryPool(device_, pool_, nullptr);
}

std::vector<std::pair<std::string, double>> TimestampPool::Results() const {
    std::vector<std::pair<std::string, double>> out;
    if (!pool_ || names_.empty()) return out;
    std::vector<uint64_t> ticks(2 * names_.size());
    FOVRT_VK(vkGetQueryPoolResults(device_, pool_, 0, uint32_t(ticks.size()), ticks.size() * sizeof(uint64_t),
                                   ticks.data(), sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    for (size_t i = 0; i < names_.size(); ++i)
        out.emplace_back(names_[i], double(ticks[2 * i + 1] - ticks[2 * i]) * periodNs_ * 1e-6);
    return out;
}

VkCommandBuffer AllocateCommandBuffer(VkDevice device, VkCommandPool pool) {
    auto info = VkInit<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    info.commandPool = pool;
    info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    info.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    FOVRT_VK(vkAllocateCommandBuffers(device, &info, &cmd));
    return cmd;
}

void RecordImageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                        VkAccessFlags srcAccess, VkAccessFlags dstAccess, VkPipelineStageFlags srcStage,
                        VkPipelineStageFlags dstStage) {
    auto b = VkInit<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
    b.oldLayout = from;
    b.newLayout = to;
    b.srcAccessMask = srcAccess;
    b.dstAccessMask = dstAccess;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

CommandSlot::CommandSlot(VulkanContext& context) : device_(context.device()), pool_(context.commandPool()) {
    cmd_ = AllocateCommandBuffer(device_, pool_);
    auto fenceInfo = VkInit<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    FOVRT_VK(vkCreateFence(device_, &fenceInfo, nullptr, &fence_));
}

CommandSlot& CommandSlot::operator=(CommandSlot&& other) noexcept {
    if (this != &other) {
        Destroy();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        pool_ = std::exchange(other.pool_, VK_NULL_HANDLE);
        cmd_ = std::exchange(other.cmd_, VK_NULL_HANDLE);
        fence_ = std::exchange(other.fence_, VK_NULL_HANDLE);
    }
    return *this;
}

CommandSlot::~CommandSlot() { Destroy(); }

void CommandSlot::Destroy() {
    if (fence_) vkDestroyFence(device_, fence_, nullptr);
    if (cmd_) vkFreeCommandBuffers(device_, pool_, 1, &cmd_);
    fence_ = VK_NULL_HANDLE;
    cmd_ = VK_NULL_HANDLE;
}

CommandRecorder::CommandRecorder(VulkanContext& context, TimestampPool* timestamps)
    : context_(context), timestamps_(timestamps && timestamps->enabled() ? timestamps : nullptr), owned_(context) {
    cmd_ = owned_.cmd_;
    fence_ = owned_.fence_;
    Begin();
}

CommandRecorder::CommandRecorder(VulkanContext& context, CommandSlot& slot, TimestampPool* timestamps)
    : context_(context), timestamps_(timestamps && timestamps->enabled() ? timestamps : nullptr) {
    FOVRT_CHECK(slot.valid());
    cmd_ = slot.cmd_;
    fence_ = slot.fence_;
    Begin();
}

CommandRecorder::~CommandRecorder() {
    // Unsubmitted work is dropped; the command buffer goes back to the initial state so a slot
    // can record again (the owned slot frees it).
    if (recording_) {
        vkEndCommandBuffer(cmd_);
        vkResetCommandBuffer(cmd_, 0);
    }
}

void CommandRecorder::Begin(bool resetTimestamps) {
    auto info = VkInit<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    FOVRT_VK(vkBeginCommandBuffer(cmd_, &info));
    recording_ = true;
    if (!resetTimestamps) return;
    nextQuery_ = 0;
    if (timestamps_) {
        timestamps_->names_.clear();
        vkCmdResetQueryPool(cmd_, timestamps_->pool_, 0, timestamps_->capacity_);
    }
}

size_t CommandRecorder::Upload(const void* data, size_t bytes, Buffer& staging, size_t offset, Buffer& dst,
                               size_t dstOffset) {
    if (bytes == 0) return offset;
    FOVRT_CHECK(staging.mapped() != nullptr);
    FOVRT_CHECK_OP(offset + bytes, <=, staging.size());
    FOVRT_CHECK_OP(dstOffset + bytes, <=, dst.size());
    std::memcpy(static_cast<char*>(staging.mapped()) + offset, data, bytes);
    VkBufferCopy region{offset, dstOffset, bytes};
    vkCmdCopyBuffer(Cmd(), staging.handle(), dst.handle(), 1, &region);
    return (offset + bytes + 15) & ~size_t(15);
}

size_t CommandRecorder::Download(const Buffer& src, size_t bytes, Buffer& staging, size_t offset,
                                 size_t srcOffset) {
    if (bytes == 0) return offset;
    FOVRT_CHECK_OP(offset + bytes, <=, staging.size());
    FOVRT_CHECK_OP(srcOffset + bytes, <=, src.size());
    VkBufferCopy region{srcOffset, offset, bytes};
    vkCmdCopyBuffer(Cmd(), src.handle(), staging.handle(), 1, &region);
    return (offset + bytes + 15) & ~size_t(15);
}

void CommandRecorder::Copy(const Buffer& src, Buffer& dst, size_t bytes) {
    const size_t limit = std::min(src.size(), dst.size());
    FOVRT_CHECK_OP(bytes, <=, limit);
    VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(Cmd(), src.handle(), dst.handle(), 1, &region);
}

void CommandRecorder::Fill(Buffer& dst, uint32_t value) {
    vkCmdFillBuffer(Cmd(), dst.handle(), 0, VK_WHOLE_SIZE, value);
}

void CommandRecorder::Dispatch(const ComputePipeline& pipeline, VkDescriptorSet set, const void* push,
                               size_t pushBytes, uvec2 groups) {
    FOVRT_CHECK_OP(pushBytes, ==, size_t(pipeline.pushBytes()));
    vkCmdBindPipeline(Cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
    vkCmdBindDescriptorSets(Cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 0, 1, &set, 0, nullptr);
    if (pushBytes)
        vkCmdPushConstants(Cmd(), pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, uint32_t(pushBytes), push);
    vkCmdDispatch(Cmd(), groups.x, groups.y, 1);
}

void CommandRecorder::DispatchIndirect(const ComputePipeline& pipeline, VkDescriptorSet set, const void* push,
                                       size_t pushBytes, const Buffer& args) {
    FOVRT_CHECK_OP(pushBytes, ==, size_t(pipeline.pushBytes()));
    FOVRT_CHECK_OP(args.size(), >=, 3 * sizeof(uint32_t));
    vkCmdBindPipeline(Cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
    vkCmdBindDescriptorSets(Cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 0, 1, &set, 0, nullptr);
    if (pushBytes)
        vkCmdPushConstants(Cmd(), pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, uint32_t(pushBytes), push);
    vkCmdDispatchIndirect(Cmd(), args.handle(), 0);
}

void CommandRecorder::Barrier() {
    auto barrier = VkInit<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                            VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_HOST_READ_BIT |
                            VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
    VkPipelineStageFlags stages = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    vkCmdPipelineBarrier(Cmd(), stages,
                         stages | VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT, 0, 1, &barrier,
                         0, nullptr, 0, nullptr);
}

void CommandRecorder::BufferBarrier(const Buffer& buffer) {
    auto barrier = VkInit<VkBufferMemoryBarrier>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER);
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                            VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.buffer = buffer.handle();
    barrier.offset = 0;
    barrier.size = VK_WHOLE_SIZE;
    VkPipelineStageFlags stages = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    vkCmdPipelineBarrier(Cmd(), stages, stages, 0, 0, nullptr, 1, &barrier, 0, nullptr);
}

void CommandRecorder::BeginPass(const std::string& name) {
    if (!timestamps_) return;
    FOVRT_CHECK_OP(nextQuery_ + 2, <=, timestamps_->capacity_);
    VkCommandBuffer cmd = Cmd();
    timestamps_->names_.push_back(name);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps_->pool_, nextQuery_++);
}

void CommandRecorder::EndPass() {
    if (!timestamps_) return;
    vkCmdWriteTimestamp(Cmd(), VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps_->pool_, nextQuery_++);
}

void CommandRecorder::Flush() {
    Submit();
    Begin(/*resetTimestamps=*/false);
}

void CommandRecorder::Submit() {
    Cmd();
    FOVRT_VK(vkEndCommandBuffer(cmd_));
    recording_ = false;
    auto submit = VkInit<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd_;
    FOVRT_VK(vkResetFences(context_.device(), 1, &fence_));
    {
        auto queueLock = context_.LockQueue();
        FOVRT_VK(vkQueueSubmit(context_.queue(), 1, &submit, fence_));
    }
    FOVRT_VK(vkWaitForFences(context_.device(), 1, &fence_, VK_TRUE, UINT64_MAX));
    FOVRT_VK(vkResetCommandBuffer(cmd_, 0));
}

VkCommandBuffer CommandRecorder::Cmd() {
    if (!recording_) Begin();
    return cmd_;
}

}  // namespace fovrt
