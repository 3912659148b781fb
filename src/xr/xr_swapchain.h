// XrEyeSwapchain: one eye's OpenXR swapchain at the runtime's recommended size, and
// XrEyeImageWriter, which fills the acquired images on the device: the display pass
// (display/display_pass.h: exposure, tone curve, sRGB encode in the shader, 8 bits) composes the eye
// 1:1 into a buffer that is copied into the swapchain image (SPEC §11: images come and go in
// COLOR_ATTACHMENT_OPTIMAL). The bytes are sRGB-encoded for UNORM and SRGB formats alike (copies
// do not convert), so either shows the same picture; `--write-frames` writes these bytes as PNGs.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "display/display_pass.h"
#include "xr/xr_api.h"

namespace fovrt {

class VulkanContext;

class XrEyeSwapchain {
public:
    // The first format in the runtime's order of preference that fovrt writes (8-bit RGBA or
    // BGRA, UNORM or SRGB). fovrt::Error naming the offered formats when there is none.
    static VkFormat ChooseFormat(XrSession session);

    XrEyeSwapchain(XrSession session, VulkanContext& context, VkFormat format, uint32_t width, uint32_t height);
    ~XrEyeSwapchain();
    XrEyeSwapchain(const XrEyeSwapchain&) = delete;
    XrEyeSwapchain& operator=(const XrEyeSwapchain&) = delete;

    // xrAcquireSwapchainImage + xrWaitSwapchainImage: the image to write.
    VkImage Acquire();
    void Release();

    XrSwapchain handle() const { return swapchain_; }
    VkFormat format() const { return format_; }
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    DisplayByteOrder byteOrder() const;

private:
    VulkanContext& context_;
    XrSwapchain swapchain_ = XR_NULL_HANDLE;
    VkFormat format_;
    uint32_t width_, height_;
    std::vector<VkImage> images_;
    std::optional<uint32_t> acquired_;
};

class XrEyeImageWriter {
public:
    // keepSent: each Write also reads the composed bytes back (SentRgb8), for --write-frames.
    XrEyeImageWriter(VulkanContext& context, bool keepSent);
    ~XrEyeImageWriter();
    XrEyeImageWriter(const XrEyeImageWriter&) = delete;
    XrEyeImageWriter& operator=(const XrEyeImageWriter&) = delete;

    // Composes each eye (linear RGB, the swapchain's size) with `settings` (layout and overlay
    // are set per eye here) and writes it into the acquired images; waits for the device.
    void Write(const std::array<const Plane<vec3>*, 2>& eyes, const DisplaySettings& settings,
               const std::array<XrEyeSwapchain*, 2>& swapchains, const std::array<VkImage, 2>& images);
    double lastMs() const { return lastMs_; }  // wall clock of the last Write (record, submit, wait)
    // The bytes the last Write put into eye's swapchain image, as R,G,B rows (keepSent only):
    // the device's display transform, which may differ from the C++ one (TonemapToRgb8) by 1 in
    // a rare byte (shaders/common/display_transform.glsl).
    std::vector<uint8_t> SentRgb8(int eye) const;

private:
    VulkanContext& context_;
    std::array<DisplayPass, 2> passes_;
    bool keepSent_;
    std::array<DisplayByteOrder, 2> sentOrder_{};
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    double lastMs_ = 0.0;
};

}  // namespace fovrt
