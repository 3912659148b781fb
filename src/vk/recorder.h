// CommandRecorder: records uploads (through a staging buffer), dispatches, barriers, copies and
// timestamps into one command buffer, then submits and waits on a fence. The command buffer and
// fence come from a CommandSlot: one owned by the recorder, or a long-lived one (a denoiser's,
// reused every frame instead of allocating a command buffer and a fence per Denoise()).
// TimestampPool turns pairs of GPU timestamps into per-pass milliseconds (timestampPeriod).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/math.h"
#include "vk/allocator.h"

namespace fovrt {

class VulkanContext;
class ComputePipeline;

// One primary command buffer from `pool` (a thread records on its own pool: pools are not
// thread-safe).
VkCommandBuffer AllocateCommandBuffer(VkDevice device, VkCommandPool pool);
// A layout transition (and memory dependency) of mip 0, layer 0 of a colour image.
void RecordImageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                        VkAccessFlags srcAccess, VkAccessFlags dstAccess, VkPipelineStageFlags srcStage,
                        VkPipelineStageFlags dstStage);

class TimestampPool {
public:
    TimestampPool() = default;
    TimestampPool(VulkanContext& context, uint32_t maxPasses);
    TimestampPool(TimestampPool&& other) noexcept { *this = std::move(other); }
    TimestampPool& operator=(TimestampPool&& other) noexcept;
    TimestampPool(const TimestampPool&) = delete;
    TimestampPool& operator=(const TimestampPool&) = delete;
    ~TimestampPool();

    bool enabled() const { return pool_ != VK_NULL_HANDLE; }
    // After the submit completed: (pass name, ms) of every Begin/End pair recorded.
    std::vector<std::pair<std::string, double>> Results() const;

private:
    friend class CommandRecorder;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueryPool pool_ = VK_NULL_HANDLE;
    uint32_t capacity_ = 0;
    double periodNs_ = 1.0;
    std::vector<std::string> names_;
};

// A primary command buffer (from the context's resettable pool) and a fence, reused by every
// CommandRecorder made on it. One recorder at a time per slot; the context must outlive it.
class CommandSlot {
public:
    CommandSlot() = default;
    explicit CommandSlot(VulkanContext& context);
    CommandSlot(CommandSlot&& other) noexcept { *this = std::move(other); }
    CommandSlot& operator=(CommandSlot&& other) noexcept;
    CommandSlot(const CommandSlot&) = delete;
    CommandSlot& operator=(const CommandSlot&) = delete;
    ~CommandSlot();

    bool valid() const { return cmd_ != VK_NULL_HANDLE; }

private:
    friend class CommandRecorder;
    void Destroy();
    VkDevice device_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
};

class CommandRecorder {
public:
    // `timestamps` may be null (no timing). The recorder starts recording at construction.
    // This form allocates its own command buffer and fence (one-off work: tests, read-backs).
    explicit CommandRecorder(VulkanContext& context, TimestampPool* timestamps = nullptr);
    // Records into `slot` (reset, not freed, when the recorder ends): per-frame work.
    CommandRecorder(VulkanContext& context, CommandSlot& slot, TimestampPool* timestamps = nullptr);
    CommandRecorder(const CommandRecorder&) = delete;
    CommandRecorder& operator=(const CommandRecorder&) = delete;
    ~CommandRecorder();

    // Copies `bytes` from host memory into `staging` at `stagingOffset` and records a copy into
    // `dst` at `dstOffset`. Returns the next free staging offset.
    size_t Upload(const void* data, size_t bytes, Buffer& staging, size_t stagingOffset, Buffer& dst,
                  size_t dstOffset = 0);
    // Records a copy of `bytes` from `src` at `srcOffset` into `staging` at `stagingOffset`; the
    // data is readable at staging.mapped() + offset after Submit(). Returns the next free staging
    // offset.
    size_t Download(const Buffer& src, size_t bytes, Buffer& staging, size_t stagingOffset, size_t srcOffset = 0);
    void Copy(const Buffer& src, Buffer& dst, size_t bytes);
    void Fill(Buffer& dst, uint32_t value);
    void Dispatch(const ComputePipeline& pipeline, VkDescriptorSet set, const void* push,
                  size_t pushBytes, uvec2 groups);
    // vkCmdDispatchIndirect with the (x, y, z) group counts at offset 0 of `args` (written by an
    // earlier pass; Barrier() makes them visible to the indirect read).
    void DispatchIndirect(const ComputePipeline& pipeline, VkDescriptorSet set, const void* push,
                          size_t pushBytes, const Buffer& args);
    // Global barrier: all earlier compute/transfer writes visible to later compute/transfer/host
    // and to indirect-argument reads.
    void Barrier();
    // Barrier on one buffer (compute/transfer write → compute/transfer read/write).
    void BufferBarrier(const Buffer& buffer);
    // Timestamps around a pass (no-op without a pool).
    void BeginPass(const std::string& name);
    void EndPass();
    // The command buffer being recorded (recording begins if needed), for a pass that records its
    // own commands into a caller's command buffer (display/display_pass.h's Record) to run on this one.
    VkCommandBuffer commandBuffer() { return Cmd(); }
    // Ends recording, submits, waits on a fence. Recording again starts a new command buffer
    // (and resets the timestamp pool, so read its Results() before that).
    void Submit();
    // Submits what is recorded so far and waits, then goes on recording the same piece of work:
    // the passes' timestamps carry on (a pass may span the flush). For work whose host data
    // streams through a buffer smaller than the whole (vk/transfer_ring.h).
    void Flush();

private:
    void Begin(bool resetTimestamps = true);
    VkCommandBuffer Cmd();  // begins recording when needed
    VulkanContext& context_;
    TimestampPool* timestamps_;
    CommandSlot owned_;  // valid only for the one-off form
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    uint32_t nextQuery_ = 0;
    bool recording_ = false;
};

}  // namespace fovrt
