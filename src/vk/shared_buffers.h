// SharedBuffers: device buffers that several users of one Vulkan device take turns with, by
// name. The plan-driven denoisers put their transient pool's slots and their staging ring here
// (NRD's integrations share its transient pool with the application the same way): a denoiser's
// frame is recorded, submitted and waited on before Denoise() returns, so the frames of both eyes
// and of every variant never overlap, and one set of slots serves them all.
//
// A buffer is as large as its largest user asked. Growing one replaces it (the descriptor sets
// users made of the old one are stale: generation() advances); nothing shrinks while a user
// lives, and the device frees the lot with its last user (VulkanContext::SharedDeviceBuffers).
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

#include "vk/allocator.h"

namespace fovrt {

class SharedBuffers {
public:
    explicit SharedBuffers(VulkanAllocator& allocator) : allocator_(allocator) {}
    SharedBuffers(const SharedBuffers&) = delete;
    SharedBuffers& operator=(const SharedBuffers&) = delete;

    // Makes buffer `name` at least `bytes` large (of `usage`: a name keeps its first usage).
    void Reserve(const std::string& name, size_t bytes, MemoryUsage usage);
    Buffer& operator[](const std::string& name);  // one Reserve()d; fails otherwise
    // Advances whenever a buffer is replaced by a larger one.
    uint64_t generation() const { return generation_; }

    // Users: a number for each, and who ran the last frame with the buffers (their contents are
    // that user's; a plane of anyone else's earlier frame is gone).
    uint64_t NewUser() { return ++users_; }
    void Claim(uint64_t user) { holder_ = user; }
    bool HeldBy(uint64_t user) const { return holder_ == user; }

private:
    VulkanAllocator& allocator_;
    std::mutex mutex_;  // Reserve from any thread; frames themselves never overlap
    std::map<std::string, Buffer> buffers_;  // node-based: references survive other inserts
    // Atomic: a user may ask from another thread than the one that last reserved (the live loop).
    std::atomic<uint64_t> generation_{0};
    std::atomic<uint64_t> users_{0};
    std::atomic<uint64_t> holder_{0};
};

}  // namespace fovrt
