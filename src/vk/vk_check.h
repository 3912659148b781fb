// Checking every VkResult: failures become fovrt::Error naming the call and the result, so a
// missing device or driver reaches the user as one line.
#pragma once

#include <vulkan/vulkan.h>

namespace fovrt {

const char* VkResultName(VkResult result);
[[noreturn]] void VkFailed(const char* call, VkResult result);

}  // namespace fovrt

#define FOVRT_VK(call)                                                   \
    do {                                                                 \
        VkResult fovrt_vk_result_ = (call);                              \
        if (fovrt_vk_result_ != VK_SUCCESS) ::fovrt::VkFailed(#call, fovrt_vk_result_); \
    } while (0)

namespace fovrt {
// A zero-initialised Vulkan struct with its sType set (no missing-initializer warnings).
template <typename T>
T VkInit(VkStructureType type) {
    T value{};
    value.sType = type;
    return value;
}
}  // namespace fovrt
