// DisplayPass: the Vulkan host of shaders/display_compose.comp (see display_pass.h).
#include "display/display_pass.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include <fmt/format.h>

#include "core/check.h"
#include "shaders/common/display_constants.glsl"
#include "shaders/shared_constants.h"
#include "vk/context.h"
#include "vk/recorder.h"
#include "vk/vk_check.h"

namespace fovrt {
namespace {

constexpr size_t kBytesPerEyePixel = 3 * sizeof(float);

VkBufferMemoryBarrier BufferBarrier(const Buffer& buffer, VkAccessFlags src, VkAccessFlags dst) {
    auto b = VkInit<VkBufferMemoryBarrier>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER);
    b.srcAccessMask = src;
    b.dstAccessMask = dst;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.buffer = buffer.handle();
    b.offset = 0;
    b.size = VK_WHOLE_SIZE;
    return b;
}

}  // namespace

DisplayPass::DisplayPass(VulkanContext& context)
    : context_(&context),
      pipeline_(context, "display_compose", DISPLAY_COMPOSE_BINDINGS, sizeof(DisplayComposePush), 1) {
    // Placeholder eyes (no image yet: both slots empty, the window is background) and a 1×1 output,
    // so that the descriptor set is always complete.
    eyes_ = context.allocator().CreateBuffer("display.eyes", 2 * kBytesPerEyePixel);
    Resize(1, 1);
}

void DisplayPass::SetEyes(const Plane<vec3>& left, const Plane<vec3>& right, const std::array<FoveaMark, 2>& marks) {
    FOVRT_CHECK(!left.empty());
    FOVRT_CHECK(left.width() == right.width() && left.height() == right.height());
    static_assert(sizeof(vec3) == kBytesPerEyePixel, "Plane<vec3> is tightly packed float RGB");
    const ivec2 size(left.width(), left.height());
    const size_t eyeBytes = left.bytes();
    if (size != eyeSize_) {
        VulkanAllocator& alloc = context_->allocator();
        staging_ = alloc.CreateBuffer("display.staging", 2 * eyeBytes, MemoryUsage::Staging);
        eyes_ = alloc.CreateBuffer("display.eyes", 2 * eyeBytes);
        eyeSize_ = size;
        RebuildSet();
    }
    std::memcpy(staging_.mapped(), left.data(), eyeBytes);
    std::memcpy(static_cast<char*>(staging_.mapped()) + eyeBytes, right.data(), eyeBytes);
    marks_ = marks;
    uploadPending_ = true;
}

void DisplayPass::Resize(int outWidth, int outHeight) {
    FOVRT_CHECK(outWidth > 0 && outHeight > 0);
    const ivec2 size(outWidth, outHeight);
    if (size == outSize_) return;
    output_ = context_->allocator().CreateBuffer("display.output", size_t(outWidth) * size_t(outHeight) * 4);
    outSize_ = size;
    RebuildSet();
}

void DisplayPass::RebuildSet() {
    pipeline_.ResetSets();
    std::array<const Buffer*, DISPLAY_COMPOSE_BINDINGS> buffers{};
    buffers[DISPLAY_COMPOSE_B_EYES] = &eyes_;
    buffers[DISPLAY_COMPOSE_B_OUT] = &output_;
    set_ = pipeline_.MakeSet(buffers);
}

void DisplayPass::Record(VkCommandBuffer cmd, const DisplaySettings& settings, int outWidth, int outHeight) {
    FOVRT_CHECK(cmd != VK_NULL_HANDLE);
    Resize(outWidth, outHeight);
    const DisplayComposePush push = MakeDisplayComposePush(settings, eyeSize_, marks_, outSize_);
    constexpr VkPipelineStageFlags kTransferCompute = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;

    // 1. Earlier work on the same queue (the last frame's upload, composition, and the caller's
    //    copy out of Output()) is done with these buffers before they are written again.
    {
        const VkAccessFlags written = VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT;
        const std::array<VkBufferMemoryBarrier, 2> barriers = {
            BufferBarrier(eyes_, written, VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT),
            BufferBarrier(output_, written, VK_ACCESS_SHADER_WRITE_BIT)};
        vkCmdPipelineBarrier(cmd, kTransferCompute, kTransferCompute, 0, 0, nullptr, uint32_t(barriers.size()),
                             barriers.data(), 0, nullptr);
    }
    // 2. The eyes, staging → device-local, when SetEyes gave new ones (host writes to the coherent
    //    staging memory are visible to the device at submit).
    if (uploadPending_) {
        const VkBufferCopy region{0, 0, VkDeviceSize(eyeSize_.x) * VkDeviceSize(eyeSize_.y) * 2 * kBytesPerEyePixel};
        vkCmdCopyBuffer(cmd, staging_.handle(), eyes_.handle(), 1, &region);
        const VkBufferMemoryBarrier uploaded = BufferBarrier(eyes_, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT);
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 1,
                             &uploaded, 0, nullptr);
        uploadPending_ = false;
    }
    // 3. The composition, one invocation per output pixel.
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.handle());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.layout(), 0, 1, &set_, 0, nullptr);
    vkCmdPushConstants(cmd, pipeline_.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, uint32_t(outSize_.x + FOVRT_WORKGROUP_X - 1) / FOVRT_WORKGROUP_X,
                  uint32_t(outSize_.y + FOVRT_WORKGROUP_Y - 1) / FOVRT_WORKGROUP_Y, 1);
    // 4. Output() ready for the caller's vkCmdCopyBufferToImage (or a read-back copy).
    const VkBufferMemoryBarrier done = BufferBarrier(output_, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 1,
                         &done, 0, nullptr);
}

VkBufferImageCopy DisplayPass::OutputCopyRegion() const {
    VkBufferImageCopy region{};
    region.bufferOffset = 0;
    region.bufferRowLength = 0;    // tightly packed
    region.bufferImageHeight = 0;
    region.imageSubresource.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
    region.imageSubresource.mipLevel = 0;
    region.imageSubresource.baseArrayLayer = 0;
    region.imageSubresource.layerCount = 1;
    region.imageOffset = {0, 0, 0};
    region.imageExtent = {uint32_t(outSize_.x), uint32_t(outSize_.y), 1};
    return region;
}

void DisplayPass::RecordReadBack(VkCommandBuffer cmd) {
    FOVRT_CHECK(cmd != VK_NULL_HANDLE && outSize_.x > 0);
    const size_t bytes = size_t(outSize_.x) * size_t(outSize_.y) * sizeof(uint32_t);
    if (readback_.size() < bytes)
        readback_ = context_->allocator().CreateBuffer("display.readback", bytes, MemoryUsage::Staging);
    const VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd, output_.handle(), readback_.handle(), 1, &region);  // Record's barrier ordered it
    const VkBufferMemoryBarrier copied = BufferBarrier(readback_, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &copied, 0,
                         nullptr);
}

std::vector<uint32_t> DisplayPass::ReadBack() const {
    std::vector<uint32_t> pixels(size_t(outSize_.x) * size_t(outSize_.y));
    FOVRT_CHECK_OP(pixels.size() * sizeof(uint32_t), <=, readback_.size());
    std::memcpy(pixels.data(), readback_.mapped(), pixels.size() * sizeof(uint32_t));
    return pixels;
}

std::vector<uint32_t> DisplayPass::Run(const DisplaySettings& settings, int outWidth, int outHeight) {
    CommandRecorder recorder(*context_);
    Record(recorder.commandBuffer(), settings, outWidth, outHeight);
    RecordReadBack(recorder.commandBuffer());
    recorder.Submit();
    return ReadBack();
}

DisplayBenchResult BenchDisplayPass(VulkanContext& context, ivec2 outSize, ivec2 eyeSize, int repeats) {
    FOVRT_CHECK(repeats > 0);
    // Eyes with a little of everything: a gradient over [0, 2] (some clip), the overlay on.
    Plane<vec3> left(eyeSize.x, eyeSize.y), right(eyeSize.x, eyeSize.y);
    for (int y = 0; y < eyeSize.y; ++y)
        for (int x = 0; x < eyeSize.x; ++x) {
            const float u = 2.0f * float(x) / float(eyeSize.x), v = float(y) / float(eyeSize.y);
            left(x, y) = vec3(u, v, 0.5f);
            right(x, y) = vec3(v, u, 0.25f);
        }
    const vec2 centre = vec2(eyeSize) * 0.5f;
    const std::array<FoveaMark, 2> marks = {FoveaMark{centre, 0.2f * float(eyeSize.y)},
                                            FoveaMark{centre, 0.2f * float(eyeSize.y)}};
    DisplaySettings settings;  // HDR, side by side, overlay, BGRA

    DisplayPass pass(context);
    TimestampPool timestamps(context, 2);
    CommandSlot slot(context);
    std::vector<double> withUpload, composeOnly, submit;
    for (int i = 0; i <= repeats; ++i) {  // i = 0: warm-up
        pass.SetEyes(left, right, marks);
        CommandRecorder recorder(context, slot, &timestamps);
        recorder.BeginPass("upload+compose");
        pass.Record(recorder.commandBuffer(), settings, outSize.x, outSize.y);
        recorder.EndPass();
        recorder.BeginPass("compose");
        pass.Record(recorder.commandBuffer(), settings, outSize.x, outSize.y);  // nothing to upload
        recorder.EndPass();
        const auto start = std::chrono::steady_clock::now();
        recorder.Submit();
        const double wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (i == 0) continue;
        submit.push_back(wallMs);
        for (const auto& [name, ms] : timestamps.Results()) (name == "compose" ? composeOnly : withUpload).push_back(ms);
    }
    auto median = [](std::vector<double> v) {
        if (v.empty()) return 0.0;
        std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
        return v[v.size() / 2];
    };
    DisplayBenchResult r;
    r.outSize = outSize;
    r.eyeSize = eyeSize;
    r.timestamps = timestamps.enabled();
    r.uploadComposeMs = median(withUpload);
    r.composeMs = median(composeOnly);
    r.submitMs = median(submit);
    return r;
}

std::string FormatDisplayBench(const DisplayBenchResult& r) {
    const std::string sizes =
        fmt::format("display compose {}x{} (eyes {}x{})", r.outSize.x, r.outSize.y, r.eyeSize.x, r.eyeSize.y);
    if (!r.timestamps)
        return fmt::format("{}: {:.3f} ms per submit of upload + 2 compositions (no GPU timestamps)", sizes,
                           r.submitMs);
    return fmt::format("{}: {:.3f} ms, with the eyes' upload {:.3f} ms (GPU); submit+wait of both {:.3f} ms", sizes,
                       r.composeMs, r.uploadComposeMs, r.submitMs);
}

}  // namespace fovrt
