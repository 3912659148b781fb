// The one allocator every Vulkan buffer goes through: plain vkAllocateMemory per buffer (Debian
// ships no VMA; a few dozen buffers per denoiser make sub-allocation unnecessary), with an
// account of every live buffer by name and size, so `fovrt memory`'s plan can be checked
// against what was really allocated. Buffer is move-only and frees itself.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace fovrt {

class VulkanAllocator;

enum class MemoryUsage { Device, Staging };  // device-local storage / host-visible coherent

class Buffer {
public:
    Buffer() = default;
    Buffer(Buffer&& other) noexcept { *this = std::move(other); }
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;
    ~Buffer() { Release(); }

    VkBuffer handle() const { return buffer_; }
    size_t size() const { return size_; }
    const std::string& name() const { return name_; }
    bool valid() const { return buffer_ != VK_NULL_HANDLE; }
    // Host pointer of a Staging buffer (persistently mapped); null for Device buffers that are
    // not host visible.
    void* mapped() const { return mapped_; }
    void Release();

private:
    friend class VulkanAllocator;
    VulkanAllocator* allocator_ = nullptr;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    void* mapped_ = nullptr;
    size_t size_ = 0;
    std::string name_;
    uint64_t id_ = 0;
};

struct AllocationRecord {
    std::string name;
    size_t bytes = 0;  // requested size (what the plan lists)
};

class VulkanAllocator {
public:
    VulkanAllocator() = default;
    void Init(VkPhysicalDevice physicalDevice, VkDevice device);

    // A storage + transfer buffer of `bytes` (≥ 4; rounded up to 4). fovrt::Error on failure.
    Buffer CreateBuffer(const std::string& name, size_t bytes, MemoryUsage usage = MemoryUsage::Device);

    // Live buffers, in creation order.
    std::vector<AllocationRecord> LiveAllocations() const;
    size_t LiveBytes() const;
    size_t PeakBytes() const { return peakBytes_; }

private:
    friend class Buffer;
    void Free(Buffer& buffer);
    uint32_t FindMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                            VkMemoryPropertyFlags preferred) const;

    VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkPhysicalDeviceMemoryProperties memoryProperties_{};
    mutable std::mutex mutex_;
    std::map<uint64_t, AllocationRecord> live_;
    uint64_t nextId_ = 1;
    size_t liveBytes_ = 0;
    size_t peakBytes_ = 0;
};

}  // namespace fovrt
