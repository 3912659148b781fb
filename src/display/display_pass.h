// DisplayPass: the display composition (display/display_compose.h) on the Vulkan device, recorded into
// the caller's command buffer so that a window thread can follow it with the copy into its
// swapchain image and submit both together:
//
//   pass.SetEyes(left, right, marks);                  // memcpy into host-visible staging
//   pass.Record(cmd, settings, extent.width, extent.height);
//   (transition the swapchain image to TRANSFER_DST_OPTIMAL)
//   VkBufferImageCopy region = pass.OutputCopyRegion();
//   vkCmdCopyBufferToImage(cmd, pass.Output().handle(), image, TRANSFER_DST_OPTIMAL, 1, &region);
//   (transition the image on to PRESENT_SRC_KHR, or COLOR_ATTACHMENT_OPTIMAL for an ImGui pass)
//
// The swapchain needs VK_IMAGE_USAGE_TRANSFER_DST_BIT and a B8G8R8A8 or R8G8B8A8 format, UNORM or
// SRGB (DisplaySettings::byteOrder names which; the bytes are sRGB-encoded for both, since copies
// do not convert). The eyes live in device-local buffers, uploaded from the staging buffer inside
// Record only when SetEyes gave new ones; Record's barriers order it after any earlier Record on
// the same queue and make Output() ready for a transfer read, so it is correct on discrete GPUs,
// not only on lavapipe's shared memory.
//
// Host-side hazards the caller owns (as with any staging buffer): SetEyes, Resize and a Record
// that changes the output size must not run while a command buffer with an earlier Record is still
// pending on the device: wait for its fence first (a window does before it re-records a frame, and
// idles the device before it recreates its swapchain).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/image.h"
#include "core/math.h"
#include "display/display_compose.h"
#include "vk/allocator.h"
#include "vk/pipeline.h"

namespace fovrt {

class VulkanContext;

class DisplayPass {
public:
    // Builds the display_compose pipeline. Until SetEyes, Record composes the background alone.
    explicit DisplayPass(VulkanContext& context);
    DisplayPass(DisplayPass&&) noexcept = default;
    DisplayPass& operator=(DisplayPass&&) noexcept = default;

    // Copies both eyes (W×H alike, linear RGB) into the staging buffer and keeps the overlay marks;
    // the next Record uploads them. A new eye size reallocates the eye buffers.
    void SetEyes(const Plane<vec3>& left, const Plane<vec3>& right, const std::array<FoveaMark, 2>& marks);
    // New overlay marks for the eyes already set (the gaze moves faster than frames arrive).
    void SetMarks(const std::array<FoveaMark, 2>& marks) { marks_ = marks; }
    // The window's swapchain extent: reallocates Output() when it changes (no-op otherwise).
    void Resize(int outWidth, int outHeight);

    // Records into cmd (recording, compute-capable queue of this context): a barrier after earlier
    // uses of the pass's buffers, the eye upload when pending, the composition of an
    // outWidth × outHeight window, and a barrier making Output() readable by a transfer. Resizes
    // first when the extent changed.
    void Record(VkCommandBuffer cmd, const DisplaySettings& settings, int outWidth, int outHeight);

    // outW·outH packed pixels, row-major, row 0 at the top (tightly packed: bufferRowLength 0).
    const Buffer& Output() const { return output_; }
    // The region copying all of Output() into mip 0, layer 0 of a colour image of outputSize().
    VkBufferImageCopy OutputCopyRegion() const;
    ivec2 outputSize() const { return outSize_; }
    ivec2 eyeSize() const { return eyeSize_; }

    // Records, after a Record into the same command buffer, a copy of Output() into the pass's
    // host-visible read-back buffer and a barrier making it readable by the host. Once that command
    // buffer has completed, ReadBack() returns the pixels as written (what a copy put into a
    // swapchain image), one uint32 each, outputSize() of them.
    void RecordReadBack(VkCommandBuffer cmd);
    std::vector<uint32_t> ReadBack() const;

    // Records on its own command buffer, submits, waits and reads Output() back (tests,
    // screenshots): Record, RecordReadBack, ReadBack.
    std::vector<uint32_t> Run(const DisplaySettings& settings, int outWidth, int outHeight);

private:
    void RebuildSet();

    VulkanContext* context_ = nullptr;
    ComputePipeline pipeline_;
    Buffer staging_;  // host-visible: left eye, then right eye, float[2·3·W·H]
    Buffer eyes_;     // device-local, the same layout
    Buffer output_;   // device-local, uint[outW·outH]
    Buffer readback_; // host-visible, RecordReadBack only
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    ivec2 eyeSize_{0};
    ivec2 outSize_{0};
    std::array<FoveaMark, 2> marks_{};
    bool uploadPending_ = false;
};

// Cost of one composition on the device, for `fovrt bench` (median over repeats, after a warm-up).
struct DisplayBenchResult {
    ivec2 outSize{0};
    ivec2 eyeSize{0};
    bool timestamps = false;      // GPU timestamps available (else only the wall clock)
    double uploadComposeMs = 0;   // GPU: upload of both eyes + composition
    double composeMs = 0;         // GPU: composition alone (eyes already on the device)
    double submitMs = 0;          // wall clock of the submit-and-wait of both
};
DisplayBenchResult BenchDisplayPass(VulkanContext& context, ivec2 outSize = ivec2(1280, 720),
                                    ivec2 eyeSize = ivec2(640, 720), int repeats = 20);
// One line: "display compose 1280x720 (eyes 640x720): 0.31 ms, with upload 1.2 ms, …".
std::string FormatDisplayBench(const DisplayBenchResult& result);

}  // namespace fovrt
