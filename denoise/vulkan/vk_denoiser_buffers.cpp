#include "denoise/vulkan/vk_denoiser_buffers.h"

#include <cstring>

#include <glm/gtc/packing.hpp>

#include "core/check.h"
#include "core/error.h"
#include "denoise/transient_pool.h"

namespace fovrt {

void DenoiserBuffers::Allocate(VulkanContext& context, const DenoiserPlan& plan) {
    Release();
    std::vector<bool> staging(plan.buffers.size(), false);
    for (const PlanePlacement& p : plan.planes) {
        FOVRT_CHECK(p.allocation < plan.buffers.size() && p.bytes <= plan.buffers[p.allocation].bytes);
        staging[p.allocation] = staging[p.allocation] || IsStaging(p.key.id.kind);
        planes_[p.key] = {p.allocation, p.bytes, HeldAfterFrame(plan, p.key)};
    }
    shared_ = context.SharedDeviceBuffers();
    user_ = shared_->NewUser();
    for (size_t i = 0; i < plan.buffers.size(); ++i) {
        const BufferPlan& b = plan.buffers[i];
        const MemoryUsage usage = staging[i] ? MemoryUsage::Staging : MemoryUsage::Device;
        sharedNames_.push_back(b.shared ? b.name : std::string());
        if (b.shared) {
            shared_->Reserve(b.name, b.bytes, usage);
            allocations_.emplace_back();
        } else {
            allocations_.push_back(context.allocator().CreateBuffer(b.name, b.bytes, usage));
        }
    }
}

Buffer& DenoiserBuffers::Allocation(size_t allocation) {
    return Shared(allocation) ? (*shared_)[sharedNames_[allocation]] : allocations_[allocation];
}

const DenoiserBuffers::Placement& DenoiserBuffers::Find(const BufferKey& key) const {
    auto it = planes_.find(key);
    if (it == planes_.end()) Fail("{}: no buffer '{}' in the memory plan", owner_, BufferName(key));
    return it->second;
}

Buffer& DenoiserBuffers::operator[](const BufferKey& key) { return Allocation(Find(key).allocation); }

size_t DenoiserBuffers::Bytes(const BufferKey& key) const { return Find(key).bytes; }

// Only the own buffers: what the shared ones hold (transient planes, staging) is written whole
// within a frame before it is read, so no earlier value survives to be dropped.
void DenoiserBuffers::RecordClear(CommandRecorder& rec, Precision precision) {
    for (const auto& [key, placement] : planes_)
        if (!Shared(placement.allocation)) rec.Fill(allocations_[placement.allocation], ClearValue(key.id.kind, precision));
}

std::vector<uint8_t> DenoiserBuffers::Read(VulkanContext& context, Buffer& src, size_t bytes) {
    Buffer tmp = context.allocator().CreateBuffer("readback:" + src.name(), bytes, MemoryUsage::Staging);
    CommandRecorder rec(context);
    rec.Download(src, bytes, tmp, 0);
    rec.Barrier();
    rec.Submit();
    std::vector<uint8_t> out(bytes);
    std::memcpy(out.data(), tmp.mapped(), bytes);
    return out;
}

std::vector<uint8_t> DenoiserBuffers::Read(VulkanContext& context, const BufferKey& key) {
    const Placement& p = Find(key);
    if (!p.heldAfterFrame)
        Fail("{}: '{}' is gone after the frame (a later plane reused its transient slot)", owner_, BufferName(key));
    if (Shared(p.allocation) && !shared_->HeldBy(user_))
        Fail("{}: '{}' is gone (another denoiser on the device has run a frame with the shared transient pool since)",
             owner_, BufferName(key));
    return Read(context, Allocation(p.allocation), p.bytes);
}

std::vector<uint8_t> DenoiserBuffers::Read(VulkanContext& context, const std::string& name) {
    for (const auto& [key, placement] : planes_)
        if (BufferName(key) == name) return Read(context, key);
    Fail("{}: no buffer '{}' in the memory plan", owner_, name);
}

bool DenoiserBuffers::Readable(const std::string& name) const {
    for (const auto& [key, placement] : planes_)
        if (BufferName(key) == name)
            return placement.heldAfterFrame && (!Shared(placement.allocation) || shared_->HeldBy(user_));
    return false;
}

std::vector<float> DenoiserBuffers::ReadFloats(VulkanContext& context, const BufferKey& key, size_t scalarBytes) {
    FOVRT_CHECK(scalarBytes == 2 || scalarBytes == 4);
    const std::vector<uint8_t> bytes = Read(context, key);
    std::vector<float> out(bytes.size() / scalarBytes);
    if (scalarBytes == 4) {
        std::memcpy(out.data(), bytes.data(), out.size() * sizeof(float));
    } else {
        for (size_t i = 0; i < out.size(); ++i) {
            uint16_t half;
            std::memcpy(&half, bytes.data() + 2 * i, sizeof(half));
            out[i] = glm::unpackHalf1x16(half);
        }
    }
    return out;
}

void DenoiserBuffers::ReadPlane(VulkanContext& context, const BufferKey& key, int width, int height,
                                size_t scalarBytes, Plane<float>& out) {
    std::vector<float> values = ReadFloats(context, key, scalarBytes);
    const size_t pixels = size_t(width) * size_t(height);
    if (values.size() != pixels)
        Fail("{}: buffer '{}' holds {} scalars, not one per pixel of {}x{}", owner_, BufferName(key),
             values.size(), width, height);
    out.Resize(width, height);
    std::memcpy(out.data(), values.data(), out.bytes());
}

std::vector<PassTiming> PassTimings(const TimestampPool& timestamps) {
    std::vector<PassTiming> timings;
    for (auto& [pass, ms] : timestamps.Results()) timings.push_back({pass, ms});
    return timings;
}

}  // namespace fovrt
