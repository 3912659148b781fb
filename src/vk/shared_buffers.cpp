#include "vk/shared_buffers.h"

#include "core/error.h"

namespace fovrt {

void SharedBuffers::Reserve(const std::string& name, size_t bytes, MemoryUsage usage) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = buffers_.find(name);
    if (it != buffers_.end() && it->second.size() >= bytes) return;
    if (it != buffers_.end()) {
        it->second = Buffer();  // free the smaller one first: the peak stays the larger alone
        ++generation_;
    }
    try {
        buffers_[name] = allocator_.CreateBuffer(name, bytes, usage);
    } catch (...) {
        buffers_.erase(name);  // no user finds an empty buffer under the name
        throw;
    }
}

Buffer& SharedBuffers::operator[](const std::string& name) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = buffers_.find(name);
    if (it == buffers_.end()) Fail("shared device buffers: none named '{}'", name);
    return it->second;
}

}  // namespace fovrt
