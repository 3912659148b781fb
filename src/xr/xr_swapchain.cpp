#include "xr/xr_swapchain.h"

#include <chrono>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/check.h"
#include "core/error.h"
#include "vk/context.h"
#include "vk/recorder.h"
#include "vk/vk_check.h"

namespace fovrt {
namespace {

bool Writable(int64_t format) {
    switch (format) {
        case VK_FORMAT_R8G8B8A8_SRGB:
        case VK_FORMAT_B8G8R8A8_SRGB:
        case VK_FORMAT_R8G8B8A8_UNORM:
        case VK_FORMAT_B8G8R8A8_UNORM: return true;
        default: return false;
    }
}

}  // namespace

VkFormat XrEyeSwapchain::ChooseFormat(XrSession session) {
    uint32_t count = 0;
    XrCheck(xrEnumerateSwapchainFormats(session, 0, &count, nullptr), "xrEnumerateSwapchainFormats");
    std::vector<int64_t> formats(count);
    XrCheck(xrEnumerateSwapchainFormats(session, count, &count, formats.data()), "xrEnumerateSwapchainFormats");
    for (int64_t f : formats)
        if (Writable(f)) return VkFormat(f);
    Fail("the OpenXR runtime offers no 8-bit RGBA/BGRA swapchain format (offered VkFormats: {})",
         fmt::join(formats, ", "));
}

XrEyeSwapchain::XrEyeSwapchain(XrSession session, VulkanContext& context, VkFormat format, uint32_t width,
                               uint32_t height)
    : context_(context), format_(format), width_(width), height_(height) {
    auto info = XrInit<XrSwapchainCreateInfo>(XR_TYPE_SWAPCHAIN_CREATE_INFO);
    info.usageFlags = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT | XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT;
    info.format = format;
    info.sampleCount = 1;
    info.width = width;
    info.height = height;
    info.faceCount = 1;
    info.arraySize = 1;
    info.mipCount = 1;
    XrCheck(xrCreateSwapchain(session, &info, &swapchain_), "xrCreateSwapchain");
    uint32_t count = 0;
    XrCheck(xrEnumerateSwapchainImages(swapchain_, 0, &count, nullptr), "xrEnumerateSwapchainImages");
    std::vector<XrSwapchainImageVulkan2KHR> images(count, XrInit<XrSwapchainImageVulkan2KHR>(XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR));
    XrCheck(xrEnumerateSwapchainImages(swapchain_, count, &count,
                                       reinterpret_cast<XrSwapchainImageBaseHeader*>(images.data())),
            "xrEnumerateSwapchainImages");
    for (const auto& image : images) images_.push_back(image.image);
}

XrEyeSwapchain::~XrEyeSwapchain() {
    if (swapchain_ != XR_NULL_HANDLE) xrDestroySwapchain(swapchain_);
}

VkImage XrEyeSwapchain::Acquire() {
    auto acquire = XrInit<XrSwapchainImageAcquireInfo>(XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO);
    uint32_t index = 0;
    {
        auto queue = context_.LockQueue();
        XrCheck(xrAcquireSwapchainImage(swapchain_, &acquire, &index), "xrAcquireSwapchainImage");
    }
    auto wait = XrInit<XrSwapchainImageWaitInfo>(XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
    wait.timeout = XR_INFINITE_DURATION;
    XrCheck(xrWaitSwapchainImage(swapchain_, &wait), "xrWaitSwapchainImage");
    if (index >= images_.size()) Fail("xrAcquireSwapchainImage: image index {} of {}", index, images_.size());
    acquired_ = index;
    return images_[index];
}

void XrEyeSwapchain::Release() {
    if (!acquired_) return;
    auto release = XrInit<XrSwapchainImageReleaseInfo>(XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO);
    {
        auto queue = context_.LockQueue();
        XrCheck(xrReleaseSwapchainImage(swapchain_, &release), "xrReleaseSwapchainImage");
    }
    acquired_.reset();
}

DisplayByteOrder XrEyeSwapchain::byteOrder() const {
    return format_ == VK_FORMAT_B8G8R8A8_SRGB || format_ == VK_FORMAT_B8G8R8A8_UNORM ? DisplayByteOrder::Bgra
                                                                                       : DisplayByteOrder::Rgba;
}

XrEyeImageWriter::XrEyeImageWriter(VulkanContext& context, bool keepSent)
    : context_(context), passes_{DisplayPass(context), DisplayPass(context)}, keepSent_(keepSent) {
    auto poolInfo = VkInit<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = context.queueFamily();
    FOVRT_VK(vkCreateCommandPool(context.device(), &poolInfo, nullptr, &pool_));
    cmd_ = AllocateCommandBuffer(context.device(), pool_);
    auto fenceInfo = VkInit<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    FOVRT_VK(vkCreateFence(context.device(), &fenceInfo, nullptr, &fence_));
}

XrEyeImageWriter::~XrEyeImageWriter() {
    if (fence_) vkDestroyFence(context_.device(), fence_, nullptr);
    if (pool_) vkDestroyCommandPool(context_.device(), pool_, nullptr);
}

void XrEyeImageWriter::Write(const std::array<const Plane<vec3>*, 2>& eyes, const DisplaySettings& settings,
                             const std::array<XrEyeSwapchain*, 2>& swapchains, const std::array<VkImage, 2>& images) {
    const auto start = std::chrono::steady_clock::now();
    FOVRT_VK(vkResetCommandBuffer(cmd_, 0));
    auto begin = VkInit<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    FOVRT_VK(vkBeginCommandBuffer(cmd_, &begin));
    for (int eye = 0; eye < 2; ++eye) {
        DisplayPass& pass = passes_[size_t(eye)];
        const XrEyeSwapchain& swapchain = *swapchains[size_t(eye)];
        // No overlay marks: the headset shows the picture alone.
        pass.SetEyes(*eyes[0], *eyes[1], {});
        DisplaySettings eyeSettings = settings;
        eyeSettings.layout = eye == 0 ? DisplayLayout::LeftEye : DisplayLayout::RightEye;
        eyeSettings.overlay = false;
        eyeSettings.byteOrder = swapchain.byteOrder();
        pass.Record(cmd_, eyeSettings, int(swapchain.width()), int(swapchain.height()));
        RecordImageBarrier(cmd_, images[size_t(eye)], VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                           VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                           VK_PIPELINE_STAGE_TRANSFER_BIT);
        const VkBufferImageCopy region = pass.OutputCopyRegion();
        vkCmdCopyBufferToImage(cmd_, pass.Output().handle(), images[size_t(eye)], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               1, &region);
        if (keepSent_) pass.RecordReadBack(cmd_);
        sentOrder_[size_t(eye)] = eyeSettings.byteOrder;
        RecordImageBarrier(cmd_, images[size_t(eye)], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                           VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT);
    }
    FOVRT_VK(vkEndCommandBuffer(cmd_));
    FOVRT_VK(vkResetFences(context_.device(), 1, &fence_));
    auto submit = VkInit<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd_;
    {
        auto queue = context_.LockQueue();
        FOVRT_VK(vkQueueSubmit(context_.queue(), 1, &submit, fence_));
    }
    FOVRT_VK(vkWaitForFences(context_.device(), 1, &fence_, VK_TRUE, UINT64_MAX));
    lastMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::vector<uint8_t> XrEyeImageWriter::SentRgb8(int eye) const {
    FOVRT_CHECK(keepSent_ && (eye == 0 || eye == 1));
    return DisplayPixelsRgb8(passes_[size_t(eye)].ReadBack(), sentOrder_[size_t(eye)]);
}

}  // namespace fovrt
