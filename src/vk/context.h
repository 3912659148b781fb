// VulkanContext: the compute device the denoisers run on. Either creates its own headless
// instance/device/compute queue, or wraps handles created elsewhere (a GLFW window, or an OpenXR
// session via xrCreateVulkanInstanceKHR / xrCreateVulkanDeviceKHR) without owning them: the
// denoiser never insists on creating its own. Move-only; all state lives behind one pointer so
// buffers and pipelines may keep a stable reference to it.
#pragma once

#include <atomic>
#include <functional>
#include <mutex>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/allocator.h"

namespace fovrt {

class SharedBuffers;

enum class Validation { Auto, On, Off };  // Auto: on in Debug builds or when FOVRT_VK_VALIDATION=1

struct VulkanContextOptions {
    // A device setting (vk/device_choice.h): "auto" or "vulkan" (the preferred device) or an index.
    // "cpu" names the C++ reference, which has no context: Create() refuses it.
    std::string device = "auto";
    Validation validation = Validation::Auto;
    bool quiet = false;           // no notice when validation was asked for but is unavailable
    // A window's needs (GLFW's required instance extensions, VK_KHR_swapchain, a queue family that
    // can present): the one queue then serves compute, transfer and presentation.
    std::vector<std::string> instanceExtensions;
    std::vector<std::string> deviceExtensions;
    std::function<bool(VkInstance, VkPhysicalDevice, uint32_t queueFamily)> queueFamilyAccepts;
    // Who creates the instance and the device, and picks the physical device: vkCreateInstance,
    // the `device` setting and vkCreateDevice unless set. An OpenXR session sets all three so that
    // the runtime creates them (XR_KHR_vulkan_enable2: it adds what it needs and names the device
    // that drives the headset); the context still owns and destroys them. Each throws on failure.
    std::function<VkInstance(const VkInstanceCreateInfo&)> createInstance;
    std::function<VkPhysicalDevice(VkInstance)> pickPhysicalDevice;
    std::function<VkDevice(VkPhysicalDevice, const VkDeviceCreateInfo&)> createDevice;
};

// Handles owned by someone else (window or OpenXR). They must outlive the context.
struct ExternalVulkan {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;       // must support compute
    uint32_t queueFamily = 0;
    bool storageBuffer16BitEnabled = false;  // whether the creator enabled storageBuffer16BitAccess
};

struct VulkanDeviceInfo {
    uint32_t index = 0;
    std::string name;
    std::string type;  // "discrete", "integrated", "cpu", "virtual", "other"
    bool compute = false;  // has a compute queue (the denoisers need one)
    bool storage16 = false;  // storageBuffer16BitAccess (fp16 storage: denoise.precision)
};

class VulkanContext {
public:
    // Creates instance + device + compute queue on the device ResolveVulkanDevice picks for
    // options.device. fovrt::Error when no Vulkan device exists or the setting names none (the
    // message lists the devices).
    static VulkanContext Create(const VulkanContextOptions& options = {});
    // Wraps external handles (not destroyed by the context). Creates only a command pool.
    static VulkanContext Wrap(const ExternalVulkan& external);
    // Devices the loader reports (empty when there is no loader/ICD).
    static std::vector<VulkanDeviceInfo> ListDevices();
    // True when Create() with default options would succeed (cached after the first call).
    static bool Available();

    VulkanContext(VulkanContext&&) noexcept;
    VulkanContext& operator=(VulkanContext&&) noexcept;
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;
    ~VulkanContext();

    VkInstance instance() const;
    VkPhysicalDevice physicalDevice() const;
    VkDevice device() const;
    VkQueue queue() const;
    uint32_t queueFamily() const;
    VkCommandPool commandPool() const;
    // Held around every vkQueueSubmit / vkQueuePresentKHR: a live session submits the denoisers'
    // work from its render thread and presents from its window thread on the same queue.
    std::unique_lock<std::mutex> LockQueue() const;
    const std::string& deviceName() const;
    bool isCpuDevice() const;
    bool supports16BitStorage() const;
    bool supportsTimestamps() const;
    double timestampPeriodNs() const;
    bool validationEnabled() const;
    // Validation-layer messages of severity error / warning since creation.
    uint32_t validationErrors() const;
    uint32_t validationWarnings() const;

    VulkanAllocator& allocator();
    const VulkanAllocator& allocator() const;
    // The buffers this device's users take turns with (vk/shared_buffers.h): one set while any
    // holder of the pointer lives, created on the first call after none did.
    std::shared_ptr<SharedBuffers> SharedDeviceBuffers();

    struct State;

private:
    explicit VulkanContext(std::unique_ptr<State> state);
    std::unique_ptr<State> s_;
};

}  // namespace fovrt
