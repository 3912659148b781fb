#include "ui/imgui_layer.h"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include "core/error.h"
#include "vk/recorder.h"
#include "vk/vk_check.h"

namespace fovrt {
namespace {

void CheckImGuiVk(VkResult r) {
    if (r != VK_SUCCESS) VkFailed("ImGui Vulkan backend", r);
}

}  // namespace

ImGuiLayer::ImGuiLayer(PreviewWindow& window, VulkanContext& context) : context_(context) {
    VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16}};
    auto poolInfo = VkInit<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    poolInfo.maxSets = 16;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = sizes;
    FOVRT_VK(vkCreateDescriptorPool(context.device(), &poolInfo, nullptr, &pool_));

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working directory
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForVulkan(window.handle(), true);
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = context.instance();
    info.PhysicalDevice = context.physicalDevice();
    info.Device = context.device();
    info.QueueFamily = context.queueFamily();
    info.Queue = context.queue();
    info.DescriptorPool = pool_;
    info.MinImageCount = 2;
    info.ImageCount = std::max(2u, window.ImageCount());
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = CheckImGuiVk;
    ImGui_ImplVulkan_Init(&info, window.OverlayRenderPass());

    // The font atlas: one upload on the window's own command pool.
    VkCommandBuffer cmd = AllocateCommandBuffer(context.device(), window.CommandPool());
    auto begin = VkInit<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    FOVRT_VK(vkBeginCommandBuffer(cmd, &begin));
    ImGui_ImplVulkan_CreateFontsTexture(cmd);
    FOVRT_VK(vkEndCommandBuffer(cmd));
    auto submit = VkInit<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    {
        auto lock = context.LockQueue();
        FOVRT_VK(vkQueueSubmit(context.queue(), 1, &submit, VK_NULL_HANDLE));
        FOVRT_VK(vkQueueWaitIdle(context.queue()));
    }
    vkFreeCommandBuffers(context.device(), window.CommandPool(), 1, &cmd);
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

ImGuiLayer::~ImGuiLayer() {
    {
        auto lock = context_.LockQueue();
        vkQueueWaitIdle(context_.queue());
    }
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    vkDestroyDescriptorPool(context_.device(), pool_, nullptr);
}

void ImGuiLayer::NewFrame() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void ImGuiLayer::Render(const PreviewWindow::Frame& frame, VkRenderPass renderPass) {
    ImGui::Render();
    auto begin = VkInit<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    begin.renderPass = renderPass;
    begin.framebuffer = frame.framebuffer;
    begin.renderArea.extent = frame.extent;
    vkCmdBeginRenderPass(frame.cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), frame.cmd);
    vkCmdEndRenderPass(frame.cmd);
}

bool ImGuiLayer::WantsMouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool ImGuiLayer::WantsKeyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

}  // namespace fovrt
