#include "denoise/vulkan/vk_denoiser_buffers.h"

#include <cstring>

#include <glm/gtc/packing.hpp>

#include "core/check.h"
#include "core/error.h"

namespace fovrt {

void DenoiserBuffers::Allocate(VulkanContext& context, const DenoiserPlan& plan) {
    FOVRT_CHECK(plan.bufferKeys.size() == plan.buffers.size());
    buffers_.clear();
    for (size_t i = 0; i < plan.buffers.size(); ++i) {
        const BufferPlan& b = plan.buffers[i];
        const MemoryUsage usage = IsStaging(plan.bufferKeys[i].id.kind) ? MemoryUsage::Staging : MemoryUsage::Device;
        buffers_.emplace(plan.bufferKeys[i], context.allocator().CreateBuffer(b.name, b.bytes, usage));
    }
}

Buffer& DenoiserBuffers::operator[](const BufferKey& key) {
    auto it = buffers_.find(key);
    if (it == buffers_.end()) Fail("{}: no buffer '{}' in the memory plan", owner_, BufferName(key));
    return it->second;
}

void DenoiserBuffers::RecordClear(CommandRecorder& rec) {
    for (auto& [key, buffer] : buffers_)
        if (!IsStaging(key.id.kind)) rec.Fill(buffer, ClearValue(key.id.kind));
}

std::vector<uint8_t> DenoiserBuffers::Read(VulkanContext& context, Buffer& src) {
    Buffer tmp = context.allocator().CreateBuffer("readback:" + src.name(), src.size(), MemoryUsage::Staging);
    CommandRecorder rec(context);
    rec.Download(src, src.size(), tmp, 0);
    rec.Barrier();
    rec.Submit();
    std::vector<uint8_t> out(src.size());
    std::memcpy(out.data(), tmp.mapped(), src.size());
    return out;
}

std::vector<uint8_t> DenoiserBuffers::Read(VulkanContext& context, const BufferKey& key) {
    return Read(context, (*this)[key]);
}

std::vector<uint8_t> DenoiserBuffers::Read(VulkanContext& context, const std::string& name) {
    for (auto& [key, buffer] : buffers_)
        if (BufferName(key) == name) return Read(context, buffer);
    Fail("{}: no buffer '{}' in the memory plan", owner_, name);
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
