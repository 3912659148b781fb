// PreviewWindow: a GLFW window presenting through a Vulkan swapchain on the same VulkanContext
// the denoisers use (SPEC §10–§11). It owns the surface, the swapchain, the overlay render pass
// (load-op LOAD: the eye images are copied into the swapchain image first, ImGui draws on top),
// its own command pool (the render thread records on the context's) and one frame in flight.
// Every GLFW call happens on the thread that created the window.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/image.h"
#include "display/display_compose.h"
#include "vk/allocator.h"
#include "vk/context.h"

struct GLFWwindow;

namespace fovrt {

struct WindowOptions {
    // Every window pixel is composed on the device each present: on lavapipe a 1280×720 window
    // costs the tracer about a frame per second at 320×180 per eye (docs/performance.md, Live preview).
    int width = 960;
    int height = 540;
    std::string title = "fovrt preview";
    bool vsync = false;  // FIFO; otherwise MAILBOX or IMMEDIATE when offered (lower latency)
};

class PreviewWindow {
public:
    // Opens the window. No display, or no Vulkan support in GLFW: fovrt::Error with one line
    // pointing to `fovrt run`.
    explicit PreviewWindow(const WindowOptions& options);
    ~PreviewWindow();
    PreviewWindow(const PreviewWindow&) = delete;
    PreviewWindow& operator=(const PreviewWindow&) = delete;

    // What VulkanContext::Create needs so its device can present to this window.
    VulkanContextOptions ContextOptions(const std::string& device) const;
    // Creates the surface and swapchain on `context` (which must outlive the window's Vulkan use;
    // DetachVulkan() or the destructor releases it). No surface support: one-line fovrt::Error.
    void AttachVulkan(VulkanContext& context);
    void DetachVulkan();

    GLFWwindow* handle() const { return window_; }
    bool ShouldClose() const;
    VkRenderPass OverlayRenderPass() const { return renderPass_; }
    VkFormat Format() const { return format_; }
    uint32_t ImageCount() const { return uint32_t(images_.size()); }
    VkCommandPool CommandPool() const { return pool_; }
    const char* PresentModeName() const;

    struct Frame {
        VkCommandBuffer cmd = VK_NULL_HANDLE;  // recording
        uint32_t imageIndex = 0;
        VkImage image = VK_NULL_HANDLE;        // in TRANSFER_DST_OPTIMAL, contents undefined
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
        VkExtent2D extent{};
    };
    // Waits for the previous frame, acquires the next image and begins its command buffer.
    // nullopt when the window is minimised or the swapchain was out of date (recreated: try again).
    std::optional<Frame> BeginFrame();
    // Records the overlay pass's end state, submits and presents. With capture = true the
    // presented image is also copied to host memory (read by TakeCapture).
    void EndFrame(const Frame& frame, bool capture = false);
    // The swapchain format's byte order (what the display pass must write).
    DisplayByteOrder ByteOrder() const;
    // Waits for the last submitted frame and returns its captured pixels (0xRRGGBB, sRGB-encoded as
    // presented), or nullopt when the last EndFrame did not capture.
    std::optional<Plane<uint32_t>> TakeCapture();
    void WaitIdle();

private:
    void CreateVulkanObjects();
    void CreateSwapchain();
    void DestroySwapchain();

    GLFWwindow* window_ = nullptr;
    WindowOptions options_;
    VulkanContext* context_ = nullptr;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkPresentModeKHR presentMode_ = VK_PRESENT_MODE_FIFO_KHR;
    VkExtent2D extent_{};
    std::vector<VkImage> images_;
    std::vector<VkImageView> views_;
    std::vector<VkFramebuffer> framebuffers_;
    VkRenderPass renderPass_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence inFlight_ = VK_NULL_HANDLE;
    VkSemaphore acquired_ = VK_NULL_HANDLE;
    std::vector<VkSemaphore> rendered_;  // one per swapchain image (presentation may hold it)
    bool submitted_ = false;
    Buffer captureBuffer_;
    VkExtent2D captureExtent_{};
    bool captured_ = false;
};

// `--window WxH` into options (both at least 64); fovrt::Error naming the option otherwise.
void ParseWindowSize(const std::string& text, WindowOptions& options);

// Writes captured window pixels (0xRRGGBB, as TakeCapture gives them) as an 8-bit PNG, atomically.
void WriteWindowCapturePng(const std::filesystem::path& path, const Plane<uint32_t>& pixels);

}  // namespace fovrt
