#include "denoise/vulkan/vk_denoiser_buffers.h"

#include <cstring>

#include <glm/gtc/packing.hpp>

#include "core/check.h"
#include "core/error.h"
#include "denoise/memory_plan.h"

namespace fovrt {
namespace {

bool IsStaging(const std::string& name) { return name.rfind("staging", 0) == 0; }

}  // namespace

void DenoiserBuffers::Allocate(VulkanContext& context, const std::vector<BufferPlan>& plan) {
    buffers_.clear();
    for (const BufferPlan& b : plan)
        buffers_.emplace(b.name, context.allocator().CreateBuffer(
                                     b.name, b.bytes,
                                     IsStaging(b.name) ? MemoryUsage::Staging : MemoryUsage::Device));
}

Buffer& DenoiserBuffers::operator[](const std::string& name) {
    auto it = buffers_.find(name);
    if (it == buffers_.end()) Fail("{}: no buffer '{}' in the memory plan", owner_, name);
    return it->second;
}

void DenoiserBuffers::RecordClear(CommandRecorder& rec) {
    for (auto& [name, buffer] : buffers_)
        if (name.rfind("geometry.objectId.", 0) == 0)
            rec.Fill(buffer, 0xFFFFFFFFu);
        else if (!IsStaging(name))
            rec.Fill(buffer, 0u);
    rec.Barrier();
}

size_t DenoiserBuffers::RecordUploadInputs(CommandRecorder& rec, const FrameInputs& in,
                                           const std::string& side) {
    Buffer& staging = (*this)["staging"];
    size_t off = 0;
    in.ForEachPlane([&](const PlaneBytes& plane) {
        // Sample counts: each host uploads them where its staging reserves them.
        if (!UploadedWithInputs(plane.name)) return;
        // input.modulation: the frame's (de)modulation factor, albedo or F_β (memory_plan.h).
        const void* data = std::string_view(plane.name) == "albedo" ? in.Modulation().data() : plane.data;
        off = rec.Upload(data, plane.bytes, staging, off, (*this)[UploadBufferOf(plane.name, side)]);
    });
    rec.Fill((*this)["stats"], 0u);
    return off;
}

void DenoiserBuffers::RecordDownloadOutput(CommandRecorder& rec, size_t stagingOffset,
                                           size_t pixels) {
    Buffer& staging = (*this)["staging"];
    outputOffset_ = stagingOffset;
    statsOffset_ = rec.Download((*this)["output"], 12 * pixels, staging, outputOffset_);
    rec.Download((*this)["stats"], 8, staging, statsOffset_);
    rec.Barrier();
}

void DenoiserBuffers::FinishOutput(int width, int height, Plane<vec3>& output, DenoiseStats& stats) {
    output.Resize(width, height);
    const char* base = static_cast<const char*>((*this)["staging"].mapped());
    std::memcpy(output.data(), base + outputOffset_, output.bytes());
    uint32_t counters[2];
    std::memcpy(counters, base + statsOffset_, sizeof(counters));
    stats.nonFiniteSamples += counters[0];
    stats.negativeSamples += counters[1];
}

std::vector<uint8_t> DenoiserBuffers::Read(VulkanContext& context, const std::string& name) {
    Buffer& src = (*this)[name];
    Buffer tmp = context.allocator().CreateBuffer("readback:" + name, src.size(), MemoryUsage::Staging);
    CommandRecorder rec(context);
    rec.Download(src, src.size(), tmp, 0);
    rec.Barrier();
    rec.Submit();
    std::vector<uint8_t> out(src.size());
    std::memcpy(out.data(), tmp.mapped(), src.size());
    return out;
}

std::vector<float> DenoiserBuffers::ReadFloats(VulkanContext& context, const std::string& name,
                                               size_t scalarBytes) {
    FOVRT_CHECK(scalarBytes == 2 || scalarBytes == 4);
    const std::vector<uint8_t> bytes = Read(context, name);
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

void DenoiserBuffers::ReadPlane(VulkanContext& context, const std::string& name, int width,
                                int height, size_t scalarBytes, Plane<float>& out) {
    std::vector<float> values = ReadFloats(context, name, scalarBytes);
    const size_t pixels = size_t(width) * size_t(height);
    if (values.size() != pixels)
        Fail("{}: buffer '{}' holds {} scalars, not one per pixel of {}x{}", owner_, name,
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
