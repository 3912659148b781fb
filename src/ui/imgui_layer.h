// ImGuiLayer: Dear ImGui (Debian's libimgui, GLFW + Vulkan backends) drawing into the window's
// overlay render pass, on top of the eye images the display pass copied in (SPEC §10).
#pragma once

#include <vulkan/vulkan.h>

#include "ui/vulkan_window.h"

namespace fovrt {

class ImGuiLayer {
public:
    ImGuiLayer(PreviewWindow& window, VulkanContext& context);
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    void NewFrame();
    // Finishes the ImGui frame and records its draw into the overlay pass of `frame`.
    void Render(const PreviewWindow::Frame& frame, VkRenderPass renderPass);
    // Whether ImGui wants the mouse / keyboard (then they are not gaze or camera input).
    bool WantsMouse() const;
    bool WantsKeyboard() const;

private:
    VulkanContext& context_;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
};

}  // namespace fovrt
