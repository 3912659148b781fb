#include "xr/xr_connection.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace fovrt {
namespace {

namespace fs = std::filesystem;

// The loader says little about a manifest it could not use; name the file and what is wrong first.
void CheckRuntimeManifestVariable() {
    const char* path = std::getenv("XR_RUNTIME_JSON");
    if (!path || !*path) return;
    if (!fs::is_regular_file(path)) Fail("XR_RUNTIME_JSON={}: no such file", path);
    std::ifstream in(path);
    nlohmann::json manifest;
    try {
        manifest = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        Fail("XR_RUNTIME_JSON={}: not valid JSON ({})", path, e.what());
    }
    if (!manifest.is_object() || !manifest.contains("runtime") || !manifest["runtime"].is_object() ||
        !manifest["runtime"].contains("library_path") || !manifest["runtime"]["library_path"].is_string())
        Fail("XR_RUNTIME_JSON={}: not an OpenXR runtime manifest (no runtime.library_path)", path);
}

std::string NoRuntimeMessage(XrResult r) {
    const char* json = std::getenv("XR_RUNTIME_JSON");
    if (json && *json)
        return fmt::format("XR_RUNTIME_JSON={}: the OpenXR loader could not load the runtime it names ({})", json,
                           XrResultName(r));
    return fmt::format("no OpenXR runtime found ({}): install and start one (e.g. Monado) or point "
                       "XR_RUNTIME_JSON at its manifest",
                       XrResultName(r));
}

std::vector<std::string> OfferedExtensions() {
    uint32_t count = 0;
    XrResult r = xrEnumerateInstanceExtensionProperties(nullptr, 0, &count, nullptr);
    if (XR_FAILED(r)) Fail("{}", NoRuntimeMessage(r));
    std::vector<XrExtensionProperties> props(count, XrInit<XrExtensionProperties>(XR_TYPE_EXTENSION_PROPERTIES));
    r = xrEnumerateInstanceExtensionProperties(nullptr, count, &count, props.data());
    if (XR_FAILED(r)) Fail("{}", NoRuntimeMessage(r));
    std::vector<std::string> names;
    for (const auto& p : props) names.emplace_back(p.extensionName);
    return names;
}

bool Has(const std::vector<std::string>& names, const char* name) {
    for (const auto& n : names)
        if (n == name) return true;
    return false;
}

XRAPI_ATTR XrBool32 XRAPI_CALL OnDebugMessage(XrDebugUtilsMessageSeverityFlagsEXT severity,
                                              XrDebugUtilsMessageTypeFlagsEXT,
                                              const XrDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    static_cast<XrConnection*>(user)->CountValidationMessage(severity);
    const bool error = severity & XR_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    std::fprintf(stderr, "openxr %s: %s: %s\n", error ? "validation error" : "validation warning",
                 data->functionName ? data->functionName : "", data->message ? data->message : "");
    return XR_FALSE;
}

}  // namespace

XrConnection::XrConnection() {
    // The loader prints its own multi-line diagnosis of a missing runtime; fovrt's one line says
    // it. XR_LOADER_DEBUG=error (or info) set by the user still brings the loader's lines back.
    setenv("XR_LOADER_DEBUG", "none", 0);
    CheckRuntimeManifestVariable();
    const std::vector<std::string> offered = OfferedExtensions();
    if (!Has(offered, XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME))
        Fail("the OpenXR runtime does not offer {}, which fovrt needs (the runtime creates fovrt's "
             "Vulkan device through it)",
             XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME);
    std::vector<const char*> enable{XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME};
    const bool gazeOffered = Has(offered, XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME);
    if (gazeOffered) enable.push_back(XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME);
    timespec_ = Has(offered, XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME);
    if (timespec_) enable.push_back(XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME);
    debugUtils_ = Has(offered, XR_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (debugUtils_) enable.push_back(XR_EXT_DEBUG_UTILS_EXTENSION_NAME);

    auto info = XrInit<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
    std::strncpy(info.applicationInfo.applicationName, "fovrt", XR_MAX_APPLICATION_NAME_SIZE - 1);
    std::strncpy(info.applicationInfo.engineName, "fovrt", XR_MAX_ENGINE_NAME_SIZE - 1);
    info.applicationInfo.applicationVersion = 1;
    info.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
    info.enabledExtensionCount = uint32_t(enable.size());
    info.enabledExtensionNames = enable.data();
    XrResult r = xrCreateInstance(&info, &instance_);
    if (XR_FAILED(r)) Fail("{}", NoRuntimeMessage(r));

    if (debugUtils_) {
        auto messenger = XrInit<XrDebugUtilsMessengerCreateInfoEXT>(XR_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
        messenger.messageSeverities =
            XR_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | XR_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
        messenger.messageTypes = XR_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                 XR_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                 XR_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT |
                                 XR_DEBUG_UTILS_MESSAGE_TYPE_CONFORMANCE_BIT_EXT;
        messenger.userCallback = OnDebugMessage;
        messenger.userData = this;
        auto create = Proc<PFN_xrCreateDebugUtilsMessengerEXT>("xrCreateDebugUtilsMessengerEXT");
        XrCheck(create(instance_, &messenger, &messenger_), "xrCreateDebugUtilsMessengerEXT");
    }

    auto props = XrInit<XrInstanceProperties>(XR_TYPE_INSTANCE_PROPERTIES);
    XrCheck(xrGetInstanceProperties(instance_, &props), "xrGetInstanceProperties");
    runtimeName_ = fmt::format("{} {}.{}.{}", props.runtimeName, XR_VERSION_MAJOR(props.runtimeVersion),
                               XR_VERSION_MINOR(props.runtimeVersion), XR_VERSION_PATCH(props.runtimeVersion));

    auto systemInfo = XrInit<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
    systemInfo.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
    r = xrGetSystem(instance_, &systemInfo, &system_);
    if (r == XR_ERROR_FORM_FACTOR_UNAVAILABLE)
        Fail("no head-mounted display ({}): the runtime '{}' supports one but none is connected or ready",
             XrResultName(r), runtimeName_);
    if (r == XR_ERROR_FORM_FACTOR_UNSUPPORTED)
        Fail("the OpenXR runtime '{}' does not support the head-mounted display form factor ({})", runtimeName_,
             XrResultName(r));
    XrCheck(r, "xrGetSystem");

    auto gazeProps = XrInit<XrSystemEyeGazeInteractionPropertiesEXT>(XR_TYPE_SYSTEM_EYE_GAZE_INTERACTION_PROPERTIES_EXT);
    auto systemProps = XrInit<XrSystemProperties>(XR_TYPE_SYSTEM_PROPERTIES);
    if (gazeOffered) systemProps.next = &gazeProps;
    XrCheck(xrGetSystemProperties(instance_, system_, &systemProps), "xrGetSystemProperties");
    systemName_ = systemProps.systemName;
    eyeGaze_ = gazeOffered && gazeProps.supportsEyeGazeInteraction == XR_TRUE;

    uint32_t count = 0;
    XrCheck(xrEnumerateViewConfigurations(instance_, system_, 0, &count, nullptr), "xrEnumerateViewConfigurations");
    std::vector<XrViewConfigurationType> configs(count);
    XrCheck(xrEnumerateViewConfigurations(instance_, system_, count, &count, configs.data()),
            "xrEnumerateViewConfigurations");
    bool stereo = false;
    for (auto c : configs) stereo = stereo || c == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
    if (!stereo) Fail("the OpenXR system '{}' has no stereo view configuration (PRIMARY_STEREO)", systemName_);
    XrCheck(xrEnumerateViewConfigurationViews(instance_, system_, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 0,
                                              &count, nullptr),
            "xrEnumerateViewConfigurationViews");
    if (count != 2) Fail("the OpenXR system '{}' has {} stereo views, not 2", systemName_, count);
    views_.fill(XrInit<XrViewConfigurationView>(XR_TYPE_VIEW_CONFIGURATION_VIEW));
    XrCheck(xrEnumerateViewConfigurationViews(instance_, system_, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 2,
                                              &count, views_.data()),
            "xrEnumerateViewConfigurationViews");

    XrCheck(xrEnumerateEnvironmentBlendModes(instance_, system_, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 0,
                                             &count, nullptr),
            "xrEnumerateEnvironmentBlendModes");
    std::vector<XrEnvironmentBlendMode> modes(count);
    XrCheck(xrEnumerateEnvironmentBlendModes(instance_, system_, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, count,
                                             &count, modes.data()),
            "xrEnumerateEnvironmentBlendModes");
    if (modes.empty()) Fail("the OpenXR system '{}' offers no environment blend mode", systemName_);
    blendMode_ = modes.front();  // the runtime's preferred one
    for (auto m : modes)
        if (m == XR_ENVIRONMENT_BLEND_MODE_OPAQUE) blendMode_ = m;
}

XrConnection::~XrConnection() {
    if (messenger_ != XR_NULL_HANDLE) {
        auto destroy = Proc<PFN_xrDestroyDebugUtilsMessengerEXT>("xrDestroyDebugUtilsMessengerEXT");
        destroy(messenger_);
    }
    if (instance_ != XR_NULL_HANDLE) xrDestroyInstance(instance_);
}

void XrConnection::CountValidationMessage(XrDebugUtilsMessageSeverityFlagsEXT severity) {
    if (severity & XR_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) validationErrors_++;
    else validationWarnings_++;
}

XrTime XrConnection::Now() const {
    if (!timespec_) return 0;
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    auto convert = Proc<PFN_xrConvertTimespecTimeToTimeKHR>("xrConvertTimespecTimeToTimeKHR");
    XrTime time = 0;
    if (XR_FAILED(convert(instance_, &now, &time))) return 0;
    return time;
}

void XrConnection::InstallVulkanCreation(VulkanContextOptions& options) {
    // The graphics requirements must be asked before a session is created (the spec, and the core
    // validation layer, insist); fovrt's Vulkan 1.1 must lie in the runtime's range.
    auto requirements = XrInit<XrGraphicsRequirementsVulkan2KHR>(XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR);
    XrCheck(Proc<PFN_xrGetVulkanGraphicsRequirements2KHR>("xrGetVulkanGraphicsRequirements2KHR")(
                instance_, system_, &requirements),
            "xrGetVulkanGraphicsRequirements2KHR");
    const XrVersion ours = XR_MAKE_VERSION(1, 1, 0);
    if (requirements.minApiVersionSupported > ours)
        Fail("the OpenXR runtime '{}' needs Vulkan {}.{}, fovrt uses 1.1", runtimeName_,
             XR_VERSION_MAJOR(requirements.minApiVersionSupported),
             XR_VERSION_MINOR(requirements.minApiVersionSupported));

    options.createInstance = [this](const VkInstanceCreateInfo& info) {
        auto create = XrInit<XrVulkanInstanceCreateInfoKHR>(XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR);
        create.systemId = system_;
        create.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
        create.vulkanCreateInfo = &info;
        VkInstance instance = VK_NULL_HANDLE;
        VkResult vkResult = VK_SUCCESS;
        XrCheck(Proc<PFN_xrCreateVulkanInstanceKHR>("xrCreateVulkanInstanceKHR")(instance_, &create, &instance,
                                                                                 &vkResult),
                "xrCreateVulkanInstanceKHR");
        if (vkResult != VK_SUCCESS)
            Fail("xrCreateVulkanInstanceKHR: vkCreateInstance failed ({})", VkResultName(vkResult));
        return instance;
    };
    options.pickPhysicalDevice = [this](VkInstance instance) {
        auto get = XrInit<XrVulkanGraphicsDeviceGetInfoKHR>(XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR);
        get.systemId = system_;
        get.vulkanInstance = instance;
        VkPhysicalDevice device = VK_NULL_HANDLE;
        XrCheck(Proc<PFN_xrGetVulkanGraphicsDevice2KHR>("xrGetVulkanGraphicsDevice2KHR")(instance_, &get, &device),
                "xrGetVulkanGraphicsDevice2KHR");
        return device;
    };
    options.createDevice = [this](VkPhysicalDevice physicalDevice, const VkDeviceCreateInfo& info) {
        auto create = XrInit<XrVulkanDeviceCreateInfoKHR>(XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR);
        create.systemId = system_;
        create.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
        create.vulkanPhysicalDevice = physicalDevice;
        create.vulkanCreateInfo = &info;
        VkDevice device = VK_NULL_HANDLE;
        VkResult vkResult = VK_SUCCESS;
        XrCheck(Proc<PFN_xrCreateVulkanDeviceKHR>("xrCreateVulkanDeviceKHR")(instance_, &create, &device, &vkResult),
                "xrCreateVulkanDeviceKHR");
        if (vkResult != VK_SUCCESS) Fail("xrCreateVulkanDeviceKHR: vkCreateDevice failed ({})", VkResultName(vkResult));
        return device;
    };
}

}  // namespace fovrt
