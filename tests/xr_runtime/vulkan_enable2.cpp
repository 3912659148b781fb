// XR_KHR_vulkan_enable2: the runtime creates the application's VkInstance and VkDevice from the
// application's own create infos through the application's vkGetInstanceProcAddr, adding nothing:
// the runtime composites in-process on the application's device, so it needs no external-memory
// or external-semaphore extensions (lavapipe 22.3 has no VK_KHR_external_{semaphore,fence}_fd).
#include "runtime.h"

namespace fovrt::xrrt {

namespace {

XrResult XRAPI_CALL GetVulkanGraphicsRequirements2(XrInstance handle, XrSystemId id,
                                                   XrGraphicsRequirementsVulkanKHR* requirements) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstanceSystem(handle, id, &instance); XR_FAILED(r)) return r;
    if (!requirements || requirements->type != XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR)
        return XR_ERROR_VALIDATION_FAILURE;
    requirements->minApiVersionSupported = XR_MAKE_VERSION(1, 0, 0);
    requirements->maxApiVersionSupported = XR_MAKE_VERSION(1, 3, 0);
    instance->graphicsRequirementsQueried = true;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL CreateVulkanInstance(XrInstance handle,
                                         const XrVulkanInstanceCreateInfoKHR* info,
                                         VkInstance* vkInstance, VkResult* vkResult) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstance(handle, &instance); XR_FAILED(r)) return r;
    if (!info || !vkInstance || !vkResult || info->type != XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR ||
        !info->pfnGetInstanceProcAddr || !info->vulkanCreateInfo || info->createFlags != 0)
        return XR_ERROR_VALIDATION_FAILURE;
    if (XrResult r = CheckSystem(*instance, info->systemId); XR_FAILED(r)) return r;
    auto create = reinterpret_cast<PFN_vkCreateInstance>(
        info->pfnGetInstanceProcAddr(VK_NULL_HANDLE, "vkCreateInstance"));
    if (!create) return XR_ERROR_RUNTIME_FAILURE;
    *vkResult = create(info->vulkanCreateInfo, info->vulkanAllocator, vkInstance);
    if (*vkResult != VK_SUCCESS) return XR_ERROR_RUNTIME_FAILURE;
    instance->vkGetInstanceProcAddr = info->pfnGetInstanceProcAddr;
    instance->vkInstance = *vkInstance;
    return XR_SUCCESS;
}

// The first physical device the Vulkan loader lists (lavapipe on the test machines).
XrResult XRAPI_CALL GetVulkanGraphicsDevice2(XrInstance handle,
                                             const XrVulkanGraphicsDeviceGetInfoKHR* info,
                                             VkPhysicalDevice* device) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstance(handle, &instance); XR_FAILED(r)) return r;
    if (!info || !device || info->type != XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR ||
        info->vulkanInstance == VK_NULL_HANDLE)
        return XR_ERROR_VALIDATION_FAILURE;
    if (XrResult r = CheckSystem(*instance, info->systemId); XR_FAILED(r)) return r;
    uint32_t count = 1;
    VkPhysicalDevice first = VK_NULL_HANDLE;
    VkResult result = vkEnumeratePhysicalDevices(info->vulkanInstance, &count, &first);
    if ((result != VK_SUCCESS && result != VK_INCOMPLETE) || count == 0) {
        Log("xrGetVulkanGraphicsDevice2KHR: no Vulkan physical device");
        return XR_ERROR_RUNTIME_FAILURE;
    }
    *device = first;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL CreateVulkanDevice(XrInstance handle, const XrVulkanDeviceCreateInfoKHR* info,
                                       VkDevice* vkDevice, VkResult* vkResult) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstance(handle, &instance); XR_FAILED(r)) return r;
    if (!info || !vkDevice || !vkResult || info->type != XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR ||
        !info->pfnGetInstanceProcAddr || !info->vulkanCreateInfo ||
        info->vulkanPhysicalDevice == VK_NULL_HANDLE || info->createFlags != 0)
        return XR_ERROR_VALIDATION_FAILURE;
    if (XrResult r = CheckSystem(*instance, info->systemId); XR_FAILED(r)) return r;
    // vkCreateDevice is an instance-level command: query it on the instance this runtime created
    // (the application may have created its own; then the loader's trampoline serves).
    PFN_vkCreateDevice create = vkCreateDevice;
    if (instance->vkInstance != VK_NULL_HANDLE)
        if (auto f = reinterpret_cast<PFN_vkCreateDevice>(
                info->pfnGetInstanceProcAddr(instance->vkInstance, "vkCreateDevice")))
            create = f;
    *vkResult = create(info->vulkanPhysicalDevice, info->vulkanCreateInfo, info->vulkanAllocator,
                       vkDevice);
    return *vkResult == VK_SUCCESS ? XR_SUCCESS : XR_ERROR_RUNTIME_FAILURE;
}

}  // namespace

void AddVulkanFunctions(ApiTable& t) {
    const char* ext = XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME;
    t.push_back({"xrGetVulkanGraphicsRequirements2KHR", Fn(&GetVulkanGraphicsRequirements2), ext});
    t.push_back({"xrCreateVulkanInstanceKHR", Fn(&CreateVulkanInstance), ext});
    t.push_back({"xrGetVulkanGraphicsDevice2KHR", Fn(&GetVulkanGraphicsDevice2), ext});
    t.push_back({"xrCreateVulkanDeviceKHR", Fn(&CreateVulkanDevice), ext});
}

}  // namespace fovrt::xrrt
