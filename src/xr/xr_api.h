// The OpenXR headers as fovrt uses them: Vulkan graphics binding (XR_KHR_vulkan_enable2) and the
// result/state names for one-line errors. Include this instead of <openxr/...> directly, so the
// platform defines come first everywhere.
#pragma once

#include <ctime>
#include <string>

#include <vulkan/vulkan.h>

#define XR_USE_GRAPHICS_API_VULKAN
#define XR_USE_TIMESPEC
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

namespace fovrt {

// An OpenXR struct zeroed with its type set (aggregate `{XR_TYPE_...}` trips -Wextra).
template <typename T>
T XrInit(XrStructureType type) {
    T value{};
    value.type = type;
    return value;
}

// "XR_ERROR_FORM_FACTOR_UNAVAILABLE" (from the headers' reflection lists: no instance needed).
std::string XrResultName(XrResult result);
// "FOCUSED" for XR_SESSION_STATE_FOCUSED.
std::string XrSessionStateName(XrSessionState state);

// Throws fovrt::Error "<what>: XR_ERROR_..." when result is a failure; returns it otherwise
// (XR_SESSION_LOSS_PENDING and other qualified successes pass).
XrResult XrCheck(XrResult result, const char* what);

}  // namespace fovrt
