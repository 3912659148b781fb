#include "vk/allocator.h"

#include <utility>

#include "core/error.h"
#include "vk/vk_check.h"

namespace fovrt {

Buffer& Buffer::operator=(Buffer&& other) noexcept {
    if (this != &other) {
        Release();
        allocator_ = std::exchange(other.allocator_, nullptr);
        buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        mapped_ = std::exchange(other.mapped_, nullptr);
        size_ = std::exchange(other.size_, 0);
        name_ = std::move(other.name_);
        id_ = std::exchange(other.id_, 0);
    }
    return *this;
}

void Buffer::Release() {
    if (allocator_ && buffer_ != VK_NULL_HANDLE) allocator_->Free(*this);
    allocator_ = nullptr;
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
    size_ = 0;
}

void VulkanAllocator::Init(VkPhysicalDevice physicalDevice, VkDevice device) {
    physicalDevice_ = physicalDevice;
    device_ = device;
    vkGetPhysicalDeviceMemoryProperties(physicalDevice, &memoryProperties_);
}

uint32_t VulkanAllocator::FindMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                                         VkMemoryPropertyFlags preferred) const {
    for (VkMemoryPropertyFlags want : {required | preferred, required})
        for (uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i)
            if ((typeBits & (1u << i)) &&
                (memoryProperties_.memoryTypes[i].propertyFlags & want) == want)
                return i;
    Fail("no Vulkan memory type with properties 0x{:x}", required);
}

Buffer VulkanAllocator::CreateBuffer(const std::string& name, size_t bytes, MemoryUsage usage) {
    size_t size = std::max<size_t>(4, (bytes + 3) & ~size_t(3));
    auto info = VkInit<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = size;
    // Texel-buffer usage too: read-only planes of the gather-heavy passes are bound as uniform
    // texel buffers (lavapipe fetches those with vector gathers; see denoise/svgf.md "Speed").
    // Indirect usage: dispatch arguments written by a shader (svgf_moments_classify).
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT |
                 VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                 VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    Buffer b;
    FOVRT_VK(vkCreateBuffer(device_, &info, nullptr, &b.buffer_));
    b.allocator_ = this;  // from here on the destructor cleans up
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, b.buffer_, &req);
    VkMemoryPropertyFlags required = usage == MemoryUsage::Staging
                                         ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                         : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    auto alloc = VkInit<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = FindMemoryType(req.memoryTypeBits, required, 0);
    VkResult r = vkAllocateMemory(device_, &alloc, nullptr, &b.memory_);
    if (r != VK_SUCCESS)
        Fail("cannot allocate Vulkan buffer '{}' of {} bytes: {}", name, size, VkResultName(r));
    FOVRT_VK(vkBindBufferMemory(device_, b.buffer_, b.memory_, 0));
    if (usage == MemoryUsage::Staging) FOVRT_VK(vkMapMemory(device_, b.memory_, 0, VK_WHOLE_SIZE, 0, &b.mapped_));
    b.size_ = size;
    b.name_ = name;
    std::lock_guard lock(mutex_);
    b.id_ = nextId_++;
    live_[b.id_] = {name, bytes};
    liveBytes_ += bytes;
    peakBytes_ = std::max(peakBytes_, liveBytes_);
    return b;
}

void VulkanAllocator::Free(Buffer& b) {
    if (b.mapped_) vkUnmapMemory(device_, b.memory_);
    vkDestroyBuffer(device_, b.buffer_, nullptr);
    if (b.memory_ != VK_NULL_HANDLE) vkFreeMemory(device_, b.memory_, nullptr);
    std::lock_guard lock(mutex_);
    auto it = live_.find(b.id_);
    if (it != live_.end()) {
        liveBytes_ -= it->second.bytes;
        live_.erase(it);
    }
}

std::vector<AllocationRecord> VulkanAllocator::LiveAllocations() const {
    std::lock_guard lock(mutex_);
    std::vector<AllocationRecord> out;
    for (const auto& [id, rec] : live_) out.push_back(rec);
    return out;
}

size_t VulkanAllocator::LiveBytes() const {
    std::lock_guard lock(mutex_);
    return liveBytes_;
}

}  // namespace fovrt
