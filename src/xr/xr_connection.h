// XrConnection: the OpenXR instance and the head-mounted display's system (SPEC §11). It finds the
// runtime through Debian's loader, enables XR_KHR_vulkan_enable2 (required) and, when offered,
// XR_EXT_eye_gaze_interaction, XR_KHR_convert_timespec_time and XR_EXT_debug_utils (the core
// validation layer reports through it), and lets the runtime create fovrt's Vulkan instance and
// device (InstallVulkanCreation). Every reason a headset session cannot start is one line of
// fovrt::Error: no runtime, a bad XR_RUNTIME_JSON, no enable2, no HMD, an unsupported form factor.
#pragma once

#include <array>
#include <atomic>
#include <string>
#include <vector>

#include "xr/xr_api.h"

namespace fovrt {

struct VulkanContextOptions;

class XrConnection {
public:
    XrConnection();
    ~XrConnection();
    XrConnection(const XrConnection&) = delete;
    XrConnection& operator=(const XrConnection&) = delete;

    XrInstance instance() const { return instance_; }
    XrSystemId system() const { return system_; }
    const std::string& runtimeName() const { return runtimeName_; }
    const std::string& systemName() const { return systemName_; }
    // The system can deliver eye gaze (extension enabled and supportsEyeGazeInteraction).
    bool eyeGazeSupported() const { return eyeGaze_; }
    bool debugUtils() const { return debugUtils_; }
    // Per eye, PRIMARY_STEREO: recommended and maximum image sizes.
    const std::array<XrViewConfigurationView, 2>& views() const { return views_; }
    XrEnvironmentBlendMode blendMode() const { return blendMode_; }

    // The runtime creates the Vulkan instance and device of a VulkanContext built with `options`
    // and names its physical device (xrCreateVulkanInstanceKHR, xrGetVulkanGraphicsDevice2KHR,
    // xrCreateVulkanDeviceKHR). The connection must outlive the context's creation.
    void InstallVulkanCreation(VulkanContextOptions& options);

    // The runtime's clock now (XR_KHR_convert_timespec_time), 0 when it is not offered.
    XrTime Now() const;
    // Messages the core validation layer (or the runtime) sent through XR_EXT_debug_utils.
    uint32_t validationErrors() const { return validationErrors_.load(); }
    uint32_t validationWarnings() const { return validationWarnings_.load(); }
    void CountValidationMessage(XrDebugUtilsMessageSeverityFlagsEXT severity);

    template <typename Fn>
    Fn Proc(const char* name) const {
        PFN_xrVoidFunction fn = nullptr;
        XrCheck(xrGetInstanceProcAddr(instance_, name, &fn), name);
        return reinterpret_cast<Fn>(fn);
    }

private:
    XrInstance instance_ = XR_NULL_HANDLE;
    XrSystemId system_ = XR_NULL_SYSTEM_ID;
    XrDebugUtilsMessengerEXT messenger_ = XR_NULL_HANDLE;
    std::string runtimeName_, systemName_;
    bool eyeGaze_ = false;
    bool debugUtils_ = false;
    bool timespec_ = false;
    std::array<XrViewConfigurationView, 2> views_{};
    XrEnvironmentBlendMode blendMode_ = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
    std::atomic<uint32_t> validationErrors_{0}, validationWarnings_{0};
};

}  // namespace fovrt
