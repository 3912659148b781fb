#include "ui/vulkan_window.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "core/error.h"
#include "display/display_compose.h"
#include "io/png.h"
#include "vk/recorder.h"
#include "vk/vk_check.h"

namespace fovrt {
namespace {

std::string GlfwError() {
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? description : "unknown GLFW error";
}

VkSurfaceFormatKHR PickFormat(VkPhysicalDevice pd, VkSurfaceKHR surface) {
    uint32_t count = 0;
    FOVRT_VK(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &count, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    FOVRT_VK(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &count, formats.data()));
    // UNORM: the display pass writes sRGB-encoded bytes itself and ImGui's colours are sRGB too;
    // an _SRGB target would re-encode ImGui's blending.
    for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
        for (const auto& f : formats)
            if (f.format == want) return f;
    for (const auto& f : formats)
        if (f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_SRGB) return f;
    Fail("the window surface offers no 8-bit RGBA/BGRA format");
}

VkPresentModeKHR PickPresentMode(VkPhysicalDevice pd, VkSurfaceKHR surface, bool vsync) {
    if (vsync) return VK_PRESENT_MODE_FIFO_KHR;
    uint32_t count = 0;
    FOVRT_VK(vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface, &count, nullptr));
    std::vector<VkPresentModeKHR> modes(count);
    FOVRT_VK(vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface, &count, modes.data()));
    for (VkPresentModeKHR want : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
        if (std::find(modes.begin(), modes.end(), want) != modes.end()) return want;
    return VK_PRESENT_MODE_FIFO_KHR;
}

}  // namespace

PreviewWindow::PreviewWindow(const WindowOptions& options) : options_(options) {
    if (!glfwInit())
        Fail("no display for the preview window ({}): run headless with `fovrt run`", GlfwError());
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        Fail("GLFW finds no Vulkan loader with window-system support: run headless with `fovrt run`");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
    if (!window_) {
        std::string why = GlfwError();
        glfwTerminate();
        Fail("cannot open the preview window ({}): run headless with `fovrt run`", why);
    }
}

PreviewWindow::~PreviewWindow() {
    DetachVulkan();
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

VulkanContextOptions PreviewWindow::ContextOptions(const std::string& device) const {
    VulkanContextOptions options;
    options.device = device;
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (!names) Fail("GLFW lists no Vulkan surface extensions ({}): run headless with `fovrt run`", GlfwError());
    for (uint32_t i = 0; i < count; ++i) options.instanceExtensions.push_back(names[i]);
    options.deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    options.queueFamilyAccepts = [](VkInstance instance, VkPhysicalDevice pd, uint32_t family) {
        return glfwGetPhysicalDevicePresentationSupport(instance, pd, family) == GLFW_TRUE;
    };
    return options;
}

void PreviewWindow::AttachVulkan(VulkanContext& context) {
    context_ = &context;
    try {
        CreateVulkanObjects();
    } catch (...) {
        DetachVulkan();  // a half-made attachment must not outlive the context it was made on
        throw;
    }
}

void PreviewWindow::CreateVulkanObjects() {
    VulkanContext& context = *context_;
    VkDevice device = context.device();
    FOVRT_VK(glfwCreateWindowSurface(context.instance(), window_, nullptr, &surface_));
    VkBool32 supported = VK_FALSE;
    FOVRT_VK(vkGetPhysicalDeviceSurfaceSupportKHR(context.physicalDevice(), context.queueFamily(), surface_,
                                                  &supported));
    if (!supported)
        Fail("Vulkan device '{}' cannot present to this window's surface: run headless with `fovrt run`",
             context.deviceName());
    const VkSurfaceFormatKHR surfaceFormat = PickFormat(context.physicalDevice(), surface_);
    format_ = surfaceFormat.format;
    presentMode_ = PickPresentMode(context.physicalDevice(), surface_, options_.vsync);

    // The overlay pass: the swapchain image arrives holding the copied eye images
    // (TRANSFER_DST), ImGui draws on top, and it leaves ready to present.
    VkAttachmentDescription color{};
    color.format = format_;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    VkSubpassDependency dependency{};
    dependency.srcSubpass = VK_SUBPASS_EXTERNAL;
    dependency.dstSubpass = 0;
    dependency.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependency.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    dependency.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependency.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    auto rp = VkInit<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
    rp.attachmentCount = 1;
    rp.pAttachments = &color;
    rp.subpassCount = 1;
    rp.pSubpasses = &subpass;
    rp.dependencyCount = 1;
    rp.pDependencies = &dependency;
    FOVRT_VK(vkCreateRenderPass(device, &rp, nullptr, &renderPass_));

    auto poolInfo = VkInit<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = context.queueFamily();
    FOVRT_VK(vkCreateCommandPool(device, &poolInfo, nullptr, &pool_));
    cmd_ = AllocateCommandBuffer(device, pool_);
    auto fenceInfo = VkInit<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    FOVRT_VK(vkCreateFence(device, &fenceInfo, nullptr, &inFlight_));
    auto semInfo = VkInit<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
    FOVRT_VK(vkCreateSemaphore(device, &semInfo, nullptr, &acquired_));
    CreateSwapchain();
}

void PreviewWindow::CreateSwapchain() {
    VkDevice device = context_->device();
    VkSurfaceCapabilitiesKHR caps;
    FOVRT_VK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context_->physicalDevice(), surface_, &caps));
    if (caps.currentExtent.width != UINT32_MAX) {
        extent_ = caps.currentExtent;
    } else {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        extent_ = {std::clamp(uint32_t(w), caps.minImageExtent.width, caps.maxImageExtent.width),
                   std::clamp(uint32_t(h), caps.minImageExtent.height, caps.maxImageExtent.height)};
    }
    if (extent_.width == 0 || extent_.height == 0) return;  // minimised
    const VkImageUsageFlags want = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                   VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    if ((caps.supportedUsageFlags & want) != want)
        Fail("the window surface does not support transfer usage on its images");
    uint32_t imageCount = std::max(caps.minImageCount, 2u) + 1;
    if (caps.maxImageCount) imageCount = std::min(imageCount, caps.maxImageCount);
    auto info = VkInit<VkSwapchainCreateInfoKHR>(VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR);
    info.surface = surface_;
    info.minImageCount = imageCount;
    info.imageFormat = format_;
    info.imageColorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    info.imageExtent = extent_;
    info.imageArrayLayers = 1;
    info.imageUsage = want;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    info.presentMode = presentMode_;
    info.clipped = VK_TRUE;
    FOVRT_VK(vkCreateSwapchainKHR(device, &info, nullptr, &swapchain_));
    uint32_t count = 0;
    FOVRT_VK(vkGetSwapchainImagesKHR(device, swapchain_, &count, nullptr));
    images_.resize(count);
    FOVRT_VK(vkGetSwapchainImagesKHR(device, swapchain_, &count, images_.data()));
    auto semInfo = VkInit<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
    for (VkImage image : images_) {
        auto view = VkInit<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
        view.image = image;
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view.format = format_;
        view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        views_.emplace_back();
        FOVRT_VK(vkCreateImageView(device, &view, nullptr, &views_.back()));
        auto fb = VkInit<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
        fb.renderPass = renderPass_;
        fb.attachmentCount = 1;
        fb.pAttachments = &views_.back();
        fb.width = extent_.width;
        fb.height = extent_.height;
        fb.layers = 1;
        framebuffers_.emplace_back();
        FOVRT_VK(vkCreateFramebuffer(device, &fb, nullptr, &framebuffers_.back()));
        rendered_.emplace_back();
        FOVRT_VK(vkCreateSemaphore(device, &semInfo, nullptr, &rendered_.back()));
    }
}

void PreviewWindow::DestroySwapchain() {
    VkDevice device = context_->device();
    for (VkFramebuffer fb : framebuffers_) vkDestroyFramebuffer(device, fb, nullptr);
    for (VkImageView v : views_) vkDestroyImageView(device, v, nullptr);
    for (VkSemaphore s : rendered_) vkDestroySemaphore(device, s, nullptr);
    framebuffers_.clear();
    views_.clear();
    rendered_.clear();
    images_.clear();
    if (swapchain_) vkDestroySwapchainKHR(device, swapchain_, nullptr);
    swapchain_ = VK_NULL_HANDLE;
}

void PreviewWindow::WaitIdle() {
    if (!context_) return;
    if (submitted_) FOVRT_VK(vkWaitForFences(context_->device(), 1, &inFlight_, VK_TRUE, UINT64_MAX));
    submitted_ = false;
    // Presentation holds semaphores the fence does not cover; the queue going idle does.
    auto lock = context_->LockQueue();
    vkQueueWaitIdle(context_->queue());
}

void PreviewWindow::DetachVulkan() {
    if (!context_) return;
    WaitIdle();
    VkDevice device = context_->device();
    DestroySwapchain();
    captureBuffer_ = Buffer();
    vkDestroySemaphore(device, acquired_, nullptr);
    vkDestroyFence(device, inFlight_, nullptr);
    vkDestroyCommandPool(device, pool_, nullptr);
    vkDestroyRenderPass(device, renderPass_, nullptr);
    vkDestroySurfaceKHR(context_->instance(), surface_, nullptr);
    context_ = nullptr;
}

bool PreviewWindow::ShouldClose() const { return glfwWindowShouldClose(window_); }

DisplayByteOrder PreviewWindow::ByteOrder() const {
    return format_ == VK_FORMAT_R8G8B8A8_UNORM || format_ == VK_FORMAT_R8G8B8A8_SRGB ? DisplayByteOrder::Rgba
                                                                                     : DisplayByteOrder::Bgra;
}

const char* PreviewWindow::PresentModeName() const {
    switch (presentMode_) {
        case VK_PRESENT_MODE_MAILBOX_KHR: return "mailbox";
        case VK_PRESENT_MODE_IMMEDIATE_KHR: return "immediate";
        case VK_PRESENT_MODE_FIFO_KHR: return "fifo (vsync)";
        default: return "other";
    }
}

std::optional<PreviewWindow::Frame> PreviewWindow::BeginFrame() {
    VkDevice device = context_->device();
    if (submitted_) FOVRT_VK(vkWaitForFences(device, 1, &inFlight_, VK_TRUE, UINT64_MAX));
    submitted_ = false;
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    const bool resized = uint32_t(w) != extent_.width || uint32_t(h) != extent_.height;
    if (w == 0 || h == 0) return std::nullopt;
    if (!swapchain_ || resized) {
        WaitIdle();
        DestroySwapchain();
        CreateSwapchain();
        if (!swapchain_) return std::nullopt;
    }
    uint32_t index = 0;
    VkResult r = vkAcquireNextImageKHR(device, swapchain_, UINT64_MAX, acquired_, VK_NULL_HANDLE, &index);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) {
        WaitIdle();
        DestroySwapchain();
        return std::nullopt;
    }
    if (r != VK_SUCCESS && r != VK_SUBOPTIMAL_KHR) VkFailed("vkAcquireNextImageKHR", r);

    FOVRT_VK(vkResetCommandBuffer(cmd_, 0));
    auto begin = VkInit<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    FOVRT_VK(vkBeginCommandBuffer(cmd_, &begin));
    RecordImageBarrier(cmd_, images_[index], VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                 VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    return Frame{cmd_, index, images_[index], framebuffers_[index], extent_};
}

void PreviewWindow::EndFrame(const Frame& frame, bool capture) {
    VkDevice device = context_->device();
    captured_ = false;
    if (capture) {
        const size_t bytes = size_t(frame.extent.width) * frame.extent.height * 4;
        if (!captureBuffer_.valid() || captureBuffer_.size() < bytes)
            captureBuffer_ = context_->allocator().CreateBuffer("preview.capture", bytes, MemoryUsage::Staging);
        RecordImageBarrier(frame.cmd, frame.image, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                     VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {frame.extent.width, frame.extent.height, 1};
        vkCmdCopyImageToBuffer(frame.cmd, frame.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               captureBuffer_.handle(), 1, &region);
        RecordImageBarrier(frame.cmd, frame.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                     VK_ACCESS_TRANSFER_READ_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                     VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
        auto hostBarrier = VkInit<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
        hostBarrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        hostBarrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(frame.cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                             &hostBarrier, 0, nullptr, 0, nullptr);
        captureExtent_ = frame.extent;
        captured_ = true;
    }
    FOVRT_VK(vkEndCommandBuffer(frame.cmd));
    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
    auto submit = VkInit<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &acquired_;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &frame.cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &rendered_[frame.imageIndex];
    FOVRT_VK(vkResetFences(device, 1, &inFlight_));
    auto present = VkInit<VkPresentInfoKHR>(VK_STRUCTURE_TYPE_PRESENT_INFO_KHR);
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &rendered_[frame.imageIndex];
    present.swapchainCount = 1;
    present.pSwapchains = &swapchain_;
    present.pImageIndices = &frame.imageIndex;
    VkResult r;
    {
        auto lock = context_->LockQueue();
        FOVRT_VK(vkQueueSubmit(context_->queue(), 1, &submit, inFlight_));
        r = vkQueuePresentKHR(context_->queue(), &present);
    }
    submitted_ = true;
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) {
        WaitIdle();
        DestroySwapchain();
    } else if (r != VK_SUCCESS) {
        VkFailed("vkQueuePresentKHR", r);
    }
}

std::optional<Plane<uint32_t>> PreviewWindow::TakeCapture() {
    if (!captured_) return std::nullopt;
    if (submitted_) FOVRT_VK(vkWaitForFences(context_->device(), 1, &inFlight_, VK_TRUE, UINT64_MAX));
    submitted_ = false;
    Plane<uint32_t> pixels(int(captureExtent_.width), int(captureExtent_.height));
    std::memcpy(pixels.data(), captureBuffer_.mapped(), pixels.bytes());
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = DisplayPixelRgb(pixels[i], ByteOrder());
    captured_ = false;
    return pixels;
}

void ParseWindowSize(const std::string& text, WindowOptions& options) {
    if (std::sscanf(text.c_str(), "%dx%d", &options.width, &options.height) != 2 || options.width < 64 ||
        options.height < 64)
        Fail("--window {}: expected WxH with both at least 64", text);
}

void WriteWindowCapturePng(const std::filesystem::path& path, const Plane<uint32_t>& pixels) {
    // TakeCapture's 0xRRGGBB is the BGRA packing with its alpha byte cleared.
    WriteRgb8Png(path, pixels.width(), pixels.height(),
                 DisplayPixelsRgb8({pixels.data(), pixels.size()}, DisplayByteOrder::Bgra));
}

}  // namespace fovrt
