// fovrt's test OpenXR runtime (tests/xr_runtime/), driven the way an application drives a real
// runtime: through Debian's OpenXR loader, with the core validation layer enabled (its report must
// hold no error), on a VkInstance/VkDevice the runtime creates through XR_KHR_vulkan_enable2 (with
// the Vulkan validation layer when installed: the runtime's own Vulkan use must be clean too).
// Checks the interface README.md documents: state sequence, read-back images, poses, FOVs, gaze,
// the failure variables. No timing assertions.
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#define XR_USE_GRAPHICS_API_VULKAN
#define XR_USE_TIMESPEC
#include <time.h>
#include <vulkan/vulkan.h>
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>
#include <nlohmann/json.hpp>

#include "motion.h"
#include "test_support.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace fovrt::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* kRuntimeVariables[] = {
    "FOVRT_TEST_XR_SIZE", "FOVRT_TEST_XR_HZ", "FOVRT_TEST_XR_GAZE", "FOVRT_TEST_XR_GAZE_FIXED",
    "FOVRT_TEST_XR_NO_ENABLE2", "FOVRT_TEST_XR_NO_HMD", "FOVRT_TEST_XR_FORM_FACTOR_UNSUPPORTED",
    "FOVRT_TEST_XR_EXIT_AFTER", "FOVRT_TEST_XR_LOSS_AFTER", "FOVRT_TEST_XR_INSTANCE_LOSS_AFTER",
    "FOVRT_TEST_XR_DUMP"};

template <typename T>
T XrInit(XrStructureType type) {
    T value{};
    value.type = type;
    return value;
}

using Vars = std::map<std::string, std::string>;

bool HaveCoreValidation() { return std::string(FOVRT_TEST_XR_API_LAYER_PATH).size() > 0; }

// The process environment for one OpenXR client: the runtime manifest, core validation writing to
// its own report, and the FOVRT_TEST_XR_* variables given. Restored (unset) at destruction.
class XrEnvironment {
public:
    explicit XrEnvironment(const std::map<std::string, std::string>& variables) {
        static int counter = 0;
        for (const char* name : kRuntimeVariables) ::unsetenv(name);
        ::setenv("XR_RUNTIME_JSON", FOVRT_TEST_XR_RUNTIME_JSON, 1);
        report_ = ScratchDir("fovrt-xr-runtime") / ("core_validation_" + std::to_string(++counter) + ".txt");
        if (HaveCoreValidation()) {
            ::setenv("XR_API_LAYER_PATH", FOVRT_TEST_XR_API_LAYER_PATH, 1);
            ::setenv("XR_ENABLE_API_LAYERS", "XR_APILAYER_LUNARG_core_validation", 1);
            ::setenv("XR_CORE_VALIDATION_EXPORT_TYPE", "text", 1);
            ::setenv("XR_CORE_VALIDATION_FILE_NAME", report_.c_str(), 1);
        }
        for (const auto& [name, value] : variables) ::setenv(name.c_str(), value.c_str(), 1);
    }
    ~XrEnvironment() {
        for (const char* name : kRuntimeVariables) ::unsetenv(name);
    }
    // Lines of the core validation report that are errors (call after xrDestroyInstance).
    std::vector<std::string> ValidationErrors() const {
        std::vector<std::string> errors;
        std::ifstream in(report_);
        for (std::string line; std::getline(in, line);)
            if (line.find("VALID_ERROR") != std::string::npos) errors.push_back(line);
        return errors;
    }

private:
    fs::path report_;
};

#define REQUIRE_XR(call) REQUIRE((call) == XR_SUCCESS)

template <typename F>
F Proc(XrInstance instance, const char* name) {
    PFN_xrVoidFunction f = nullptr;
    REQUIRE_XR(xrGetInstanceProcAddr(instance, name, &f));
    return reinterpret_cast<F>(f);
}

XrResult CreateInstance(std::vector<const char*> extensions, XrInstance* instance) {
    auto info = XrInit<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
    std::snprintf(info.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE,
                  "xr_runtime_test");
    info.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.enabledExtensionNames = extensions.data();
    return xrCreateInstance(&info, instance);
}

std::vector<std::string> RuntimeExtensions() {
    uint32_t n = 0;
    REQUIRE_XR(xrEnumerateInstanceExtensionProperties(nullptr, 0, &n, nullptr));
    std::vector<XrExtensionProperties> props(n, XrInit<XrExtensionProperties>(XR_TYPE_EXTENSION_PROPERTIES));
    REQUIRE_XR(xrEnumerateInstanceExtensionProperties(nullptr, n, &n, props.data()));
    std::vector<std::string> names;
    for (const auto& p : props) names.push_back(p.extensionName);
    return names;
}

XrResult GetSystem(XrInstance instance, XrSystemId* system) {
    auto info = XrInit<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
    info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
    return xrGetSystem(instance, &info, system);
}

uint32_t g_vulkanErrors = 0;
VKAPI_ATTR VkBool32 VKAPI_CALL CountVulkanErrors(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT,
                                                 const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                 void*) {
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        ++g_vulkanErrors;
        std::fprintf(stderr, "Vulkan validation: %s\n", data->pMessage);
    }
    return VK_FALSE;
}

bool HasInstanceLayer(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    for (const auto& l : layers)
        if (std::string(l.layerName) == name) return true;
    return false;
}

struct Rgb {
    uint8_t r, g, b;
};

// A minimal OpenXR + Vulkan application: everything the runtime is asked for, as fovrt will ask.
struct Client {
    XrInstance instance = XR_NULL_HANDLE;
    XrSystemId system = XR_NULL_SYSTEM_ID;
    VkInstance vkInstance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    VkQueue queue = VK_NULL_HANDLE;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    XrSession session = XR_NULL_HANDLE;
    XrSpace local = XR_NULL_HANDLE, view = XR_NULL_HANDLE;
    XrActionSet actionSet = XR_NULL_HANDLE;
    XrAction gazeAction = XR_NULL_HANDLE;
    XrSpace gazeSpace = XR_NULL_HANDLE;
    struct Eye {
        XrSwapchain swapchain = XR_NULL_HANDLE;
        VkFormat format = VK_FORMAT_UNDEFINED;
        std::vector<VkImage> images;
        VkClearColorValue clear{};
    };
    Eye eyes[2];
    uint32_t width = 0, height = 0;
    std::vector<XrSessionState> states;
    bool exitingSeen = false, profileChangedSeen = false, instanceLossSeen = false;
    std::vector<std::vector<XrView>> locatedViews;  // per rendered frame
    std::vector<XrTime> predictedTimes;             // per xrWaitFrame
    XrDuration period = 0;

    // Instance with enable2, eye gaze and timespec; system; the runtime-made Vulkan device.
    void Create() {
        REQUIRE_XR(CreateInstance({XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME,
                                   XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME},
                                  &instance));
        REQUIRE_XR(GetSystem(instance, &system));
        CreateVulkan();
    }

    void CreateVulkan() {
        auto requirements = Proc<PFN_xrGetVulkanGraphicsRequirements2KHR>(
            instance, "xrGetVulkanGraphicsRequirements2KHR");
        auto createInstance = Proc<PFN_xrCreateVulkanInstanceKHR>(instance, "xrCreateVulkanInstanceKHR");
        auto graphicsDevice = Proc<PFN_xrGetVulkanGraphicsDevice2KHR>(instance, "xrGetVulkanGraphicsDevice2KHR");
        auto createDevice = Proc<PFN_xrCreateVulkanDeviceKHR>(instance, "xrCreateVulkanDeviceKHR");
        auto req = XrInit<XrGraphicsRequirementsVulkan2KHR>(XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR);
        REQUIRE_XR(requirements(instance, system, &req));
        REQUIRE(XR_VERSION_MAJOR(req.minApiVersionSupported) == 1);

        auto app = VkInit<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
        app.pApplicationName = "xr_runtime_test";
        app.apiVersion = VK_API_VERSION_1_1;
        std::vector<const char*> layers, extensions;
        bool validation = HasInstanceLayer("VK_LAYER_KHRONOS_validation");
        if (validation) {
            layers.push_back("VK_LAYER_KHRONOS_validation");
            extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        }
        auto ici = VkInit<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
        ici.pApplicationInfo = &app;
        ici.enabledLayerCount = uint32_t(layers.size());
        ici.ppEnabledLayerNames = layers.data();
        ici.enabledExtensionCount = uint32_t(extensions.size());
        ici.ppEnabledExtensionNames = extensions.data();
        auto xci = XrInit<XrVulkanInstanceCreateInfoKHR>(XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR);
        xci.systemId = system;
        xci.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
        xci.vulkanCreateInfo = &ici;
        VkResult vr = VK_ERROR_UNKNOWN;
        REQUIRE_XR(createInstance(instance, &xci, &vkInstance, &vr));
        REQUIRE(vr == VK_SUCCESS);
        if (validation) {
            auto mci = VkInit<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
            mci.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT |
                                  VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
            mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
            mci.pfnUserCallback = &CountVulkanErrors;
            auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(vkInstance, "vkCreateDebugUtilsMessengerEXT"));
            REQUIRE(create(vkInstance, &mci, nullptr, &messenger) == VK_SUCCESS);
        }

        auto gdi = XrInit<XrVulkanGraphicsDeviceGetInfoKHR>(XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR);
        gdi.systemId = system;
        gdi.vulkanInstance = vkInstance;
        REQUIRE_XR(graphicsDevice(instance, &gdi, &physicalDevice));
        uint32_t n = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &n, nullptr);
        std::vector<VkQueueFamilyProperties> families(n);
        vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &n, families.data());
        queueFamily = UINT32_MAX;
        for (uint32_t i = 0; i < n && queueFamily == UINT32_MAX; ++i)
            if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) queueFamily = i;
        REQUIRE(queueFamily != UINT32_MAX);
        float priority = 1.0f;
        auto qci = VkInit<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
        qci.queueFamilyIndex = queueFamily;
        qci.queueCount = 1;
        qci.pQueuePriorities = &priority;
        auto dci = VkInit<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
        dci.queueCreateInfoCount = 1;
        dci.pQueueCreateInfos = &qci;
        auto xdi = XrInit<XrVulkanDeviceCreateInfoKHR>(XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR);
        xdi.systemId = system;
        xdi.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
        xdi.vulkanPhysicalDevice = physicalDevice;
        xdi.vulkanCreateInfo = &dci;
        REQUIRE_XR(createDevice(instance, &xdi, &device, &vr));
        REQUIRE(vr == VK_SUCCESS);
        vkGetDeviceQueue(device, queueFamily, 0, &queue);
        auto pci = VkInit<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
        pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pci.queueFamilyIndex = queueFamily;
        REQUIRE(vkCreateCommandPool(device, &pci, nullptr, &pool) == VK_SUCCESS);
        auto cai = VkInit<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
        cai.commandPool = pool;
        cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        cai.commandBufferCount = 1;
        REQUIRE(vkAllocateCommandBuffers(device, &cai, &cmd) == VK_SUCCESS);
        auto fci = VkInit<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
        REQUIRE(vkCreateFence(device, &fci, nullptr, &fence) == VK_SUCCESS);
    }

    XrResult CreateSession() {
        auto binding = XrInit<XrGraphicsBindingVulkan2KHR>(XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR);
        binding.instance = vkInstance;
        binding.physicalDevice = physicalDevice;
        binding.device = device;
        binding.queueFamilyIndex = queueFamily;
        binding.queueIndex = 0;
        auto info = XrInit<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
        info.next = &binding;
        info.systemId = system;
        XrResult r = xrCreateSession(instance, &info, &session);
        if (r != XR_SUCCESS) return r;
        auto space = XrInit<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
        space.poseInReferenceSpace.orientation.w = 1.0f;
        space.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_LOCAL;
        REQUIRE_XR(xrCreateReferenceSpace(session, &space, &local));
        space.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_VIEW;
        REQUIRE_XR(xrCreateReferenceSpace(session, &space, &view));
        return XR_SUCCESS;
    }

    XrPath Path(const char* text) {
        XrPath p = XR_NULL_PATH;
        REQUIRE_XR(xrStringToPath(instance, text, &p));
        return p;
    }

    // The eye-gaze pose action, suggested for the gaze profile, attached, with its action space.
    void CreateGazeAction() {
        auto si = XrInit<XrActionSetCreateInfo>(XR_TYPE_ACTION_SET_CREATE_INFO);
        std::snprintf(si.actionSetName, sizeof si.actionSetName, "gaze");
        std::snprintf(si.localizedActionSetName, sizeof si.localizedActionSetName, "Gaze");
        REQUIRE_XR(xrCreateActionSet(instance, &si, &actionSet));
        auto ai = XrInit<XrActionCreateInfo>(XR_TYPE_ACTION_CREATE_INFO);
        ai.actionType = XR_ACTION_TYPE_POSE_INPUT;
        std::snprintf(ai.actionName, sizeof ai.actionName, "gaze_pose");
        std::snprintf(ai.localizedActionName, sizeof ai.localizedActionName, "Gaze pose");
        REQUIRE_XR(xrCreateAction(actionSet, &ai, &gazeAction));
        XrActionSuggestedBinding binding{gazeAction, Path("/user/eyes_ext/input/gaze_ext/pose")};
        auto suggested = XrInit<XrInteractionProfileSuggestedBinding>(XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING);
        suggested.interactionProfile = Path("/interaction_profiles/ext/eye_gaze_interaction");
        suggested.countSuggestedBindings = 1;
        suggested.suggestedBindings = &binding;
        REQUIRE_XR(xrSuggestInteractionProfileBindings(instance, &suggested));
        auto attach = XrInit<XrSessionActionSetsAttachInfo>(XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO);
        attach.countActionSets = 1;
        attach.actionSets = &actionSet;
        REQUIRE_XR(xrAttachSessionActionSets(session, &attach));
        auto spi = XrInit<XrActionSpaceCreateInfo>(XR_TYPE_ACTION_SPACE_CREATE_INFO);
        spi.action = gazeAction;
        spi.poseInActionSpace.orientation.w = 1.0f;
        REQUIRE_XR(xrCreateActionSpace(session, &spi, &gazeSpace));
    }

    // Instance, session and an RGBA8 swapchain per eye: where most session checks start.
    void StartWithSwapchains() {
        Create();
        REQUIRE_XR(CreateSession());
        CreateSwapchains(VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM);
    }

    // One swapchain per eye at the recommended size, in the given formats.
    void CreateSwapchains(VkFormat left, VkFormat right) {
        uint32_t n = 0;
        REQUIRE_XR(xrEnumerateViewConfigurationViews(instance, system,
                                                     XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 0,
                                                     &n, nullptr));
        REQUIRE(n == 2);
        std::vector<XrViewConfigurationView> views(n, XrInit<XrViewConfigurationView>(XR_TYPE_VIEW_CONFIGURATION_VIEW));
        REQUIRE_XR(xrEnumerateViewConfigurationViews(
            instance, system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, n, &n, views.data()));
        width = views[0].recommendedImageRectWidth;
        height = views[0].recommendedImageRectHeight;
        VkFormat formats[2] = {left, right};
        for (int e = 0; e < 2; ++e) {
            auto ci = XrInit<XrSwapchainCreateInfo>(XR_TYPE_SWAPCHAIN_CREATE_INFO);
            ci.usageFlags = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT |
                            XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT;
            ci.format = formats[e];
            ci.sampleCount = 1;
            ci.width = width;
            ci.height = height;
            ci.faceCount = 1;
            ci.arraySize = 1;
            ci.mipCount = 1;
            REQUIRE_XR(xrCreateSwapchain(session, &ci, &eyes[e].swapchain));
            eyes[e].format = formats[e];
            uint32_t count = 0;
            REQUIRE_XR(xrEnumerateSwapchainImages(eyes[e].swapchain, 0, &count, nullptr));
            std::vector<XrSwapchainImageVulkan2KHR> images(count, XrInit<XrSwapchainImageVulkan2KHR>(XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR));
            REQUIRE_XR(xrEnumerateSwapchainImages(
                eyes[e].swapchain, count,  &count,
                reinterpret_cast<XrSwapchainImageBaseHeader*>(images.data())));
            for (const auto& image : images) eyes[e].images.push_back(image.image);
        }
    }

    void PollEvents() {
        auto event = XrInit<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
        while (xrPollEvent(instance, &event) == XR_SUCCESS) {
            if (event.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) {
                auto& changed = reinterpret_cast<XrEventDataSessionStateChanged&>(event);
                states.push_back(changed.state);
                if (changed.state == XR_SESSION_STATE_READY) {
                    auto begin = XrInit<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
                    begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
                    REQUIRE_XR(xrBeginSession(session, &begin));
                } else if (changed.state == XR_SESSION_STATE_STOPPING) {
                    REQUIRE_XR(xrEndSession(session));
                } else if (changed.state == XR_SESSION_STATE_EXITING) {
                    exitingSeen = true;
                }
            } else if (event.type == XR_TYPE_EVENT_DATA_INTERACTION_PROFILE_CHANGED) {
                profileChangedSeen = true;
            } else if (event.type == XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING) {
                instanceLossSeen = true;
                return;  // the instance is gone: no more calls on it
            }
            event = XrInit<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
        }
    }

    XrSessionState State() const { return states.empty() ? XR_SESSION_STATE_UNKNOWN : states.back(); }
    bool Running() const {
        XrSessionState s = State();
        return s == XR_SESSION_STATE_READY || s == XR_SESSION_STATE_SYNCHRONIZED ||
               s == XR_SESSION_STATE_VISIBLE || s == XR_SESSION_STATE_FOCUSED ||
               s == XR_SESSION_STATE_STOPPING;
    }

    void Clear(const Eye& eye, uint32_t index) {
        REQUIRE(vkResetCommandBuffer(cmd, 0) == VK_SUCCESS);
        auto begin = VkInit<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
        REQUIRE(vkBeginCommandBuffer(cmd, &begin) == VK_SUCCESS);
        auto barrier = VkInit<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
        barrier.srcAccessMask = VK_ACCESS_MEMORY_READ_BIT;
        barrier.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;  // as the runtime hands it over
        barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        barrier.image = eye.images[index];
        barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             0, 0, nullptr, 0, nullptr, 1, &barrier);
        vkCmdClearColorImage(cmd, eye.images[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             &eye.clear, 1, &barrier.subresourceRange);
        barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT;
        barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        barrier.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;  // as it must be released
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                             0, 0, nullptr, 0, nullptr, 1, &barrier);
        REQUIRE(vkEndCommandBuffer(cmd) == VK_SUCCESS);
        auto submit = VkInit<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        REQUIRE(vkQueueSubmit(queue, 1, &submit, fence) == VK_SUCCESS);
        REQUIRE(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX) == VK_SUCCESS);
        REQUIRE(vkResetFences(device, 1, &fence) == VK_SUCCESS);
    }

    // xrSyncActions on the action set, then the gaze action's pose state.
    XrActionStatePose SyncGazePose() {
        XrActiveActionSet active{actionSet, XR_NULL_PATH};
        auto sync = XrInit<XrActionsSyncInfo>(XR_TYPE_ACTIONS_SYNC_INFO);
        sync.countActiveActionSets = 1;
        sync.activeActionSets = &active;
        REQUIRE_XR(xrSyncActions(session, &sync));
        auto gi = XrInit<XrActionStateGetInfo>(XR_TYPE_ACTION_STATE_GET_INFO);
        gi.action = gazeAction;
        auto pose = XrInit<XrActionStatePose>(XR_TYPE_ACTION_STATE_POSE);
        REQUIRE_XR(xrGetActionStatePose(session, &gi, &pose));
        return pose;
    }

    // One frame: wait, begin, (when shouldRender) clear each eye and submit a projection layer.
    XrFrameState Frame() {
        auto frame = XrInit<XrFrameState>(XR_TYPE_FRAME_STATE);
        REQUIRE_XR(xrWaitFrame(session, nullptr, &frame));
        REQUIRE(frame.predictedDisplayPeriod > 0);
        predictedTimes.push_back(frame.predictedDisplayTime);
        period = frame.predictedDisplayPeriod;
        REQUIRE_XR(xrBeginFrame(session, nullptr));
        std::vector<XrCompositionLayerProjectionView> projectionViews;
        auto layer = XrInit<XrCompositionLayerProjection>(XR_TYPE_COMPOSITION_LAYER_PROJECTION);
        const XrCompositionLayerBaseHeader* layers[] = {
            reinterpret_cast<const XrCompositionLayerBaseHeader*>(&layer)};
        if (frame.shouldRender) {
            auto li = XrInit<XrViewLocateInfo>(XR_TYPE_VIEW_LOCATE_INFO);
            li.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
            li.displayTime = frame.predictedDisplayTime;
            li.space = local;
            auto vs = XrInit<XrViewState>(XR_TYPE_VIEW_STATE);
            std::vector<XrView> views(2, XrInit<XrView>(XR_TYPE_VIEW));
            uint32_t n = 0;
            REQUIRE_XR(xrLocateViews(session, &li, &vs, 2, &n, views.data()));
            REQUIRE(n == 2);
            REQUIRE((vs.viewStateFlags & XR_VIEW_STATE_POSITION_VALID_BIT) != 0);
            REQUIRE((vs.viewStateFlags & XR_VIEW_STATE_ORIENTATION_VALID_BIT) != 0);
            locatedViews.push_back(views);
            for (int e = 0; e < 2; ++e) {
                uint32_t index = 0;
                REQUIRE_XR(xrAcquireSwapchainImage(eyes[e].swapchain, nullptr, &index));
                auto wi = XrInit<XrSwapchainImageWaitInfo>(XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
                wi.timeout = XR_INFINITE_DURATION;
                REQUIRE_XR(xrWaitSwapchainImage(eyes[e].swapchain, &wi));
                Clear(eyes[e], index);
                REQUIRE_XR(xrReleaseSwapchainImage(eyes[e].swapchain, nullptr));
                auto pv = XrInit<XrCompositionLayerProjectionView>(XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW);
                pv.pose = views[e].pose;
                pv.fov = views[e].fov;
                pv.subImage.swapchain = eyes[e].swapchain;
                pv.subImage.imageRect = {{0, 0}, {int32_t(width), int32_t(height)}};
                projectionViews.push_back(pv);
            }
            layer.space = local;
            layer.viewCount = 2;
            layer.views = projectionViews.data();
        }
        auto end = XrInit<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
        end.displayTime = frame.predictedDisplayTime;
        end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
        end.layerCount = frame.shouldRender ? 1 : 0;
        end.layers = layers;
        REQUIRE_XR(xrEndFrame(session, &end));
        return frame;
    }

    // Polls and renders frames until the predicate holds (bounded, so a bug cannot hang the test).
    template <typename Until>
    void RunUntil(Until until, int maxFrames = 200) {
        for (int i = 0; i < maxFrames; ++i) {
            PollEvents();
            if (until() || instanceLossSeen) return;
            if (Running() && State() != XR_SESSION_STATE_STOPPING) Frame();
        }
        FAIL("the awaited condition never held; last state " << int(State()));
    }

    void Destroy() {
        if (device) vkDeviceWaitIdle(device);
        if (session) {
            for (Eye& e : eyes)
                if (e.swapchain) xrDestroySwapchain(e.swapchain);
            if (gazeSpace) xrDestroySpace(gazeSpace);
            if (local) xrDestroySpace(local);
            if (view) xrDestroySpace(view);
            xrDestroySession(session);
        }
        if (fence) vkDestroyFence(device, fence, nullptr);
        if (pool) vkDestroyCommandPool(device, pool, nullptr);
        if (device) vkDestroyDevice(device, nullptr);
        if (messenger) {
            auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(vkInstance, "vkDestroyDebugUtilsMessengerEXT"));
            destroy(vkInstance, messenger, nullptr);
        }
        if (vkInstance) vkDestroyInstance(vkInstance, nullptr);
        if (instance) xrDestroyInstance(instance);
        *this = Client();
    }
    ~Client() {
        if (instance) Destroy();
    }
};

std::vector<std::string> ReadLines(const fs::path& file) {
    std::vector<std::string> lines;
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

std::vector<nlohmann::json> ReadFrames(const fs::path& dir) {
    std::vector<nlohmann::json> frames;
    for (const std::string& line : ReadLines(dir / "frames.jsonl"))
        frames.push_back(nlohmann::json::parse(line));
    return frames;
}

// A binary P6 PPM: every pixel must be the given colour (within 1 for rounding).
void RequireUniformPpm(const fs::path& file, uint32_t width, uint32_t height, Rgb expected) {
    std::ifstream in(file, std::ios::binary);
    REQUIRE(in);
    std::string magic;
    uint32_t w = 0, h = 0, maxValue = 0;
    in >> magic >> w >> h >> maxValue;
    in.get();
    REQUIRE(magic == "P6");
    REQUIRE(w == width);
    REQUIRE(h == height);
    REQUIRE(maxValue == 255);
    std::vector<uint8_t> pixels(size_t(w) * h * 3);
    in.read(reinterpret_cast<char*>(pixels.data()), std::streamsize(pixels.size()));
    REQUIRE(in.gcount() == std::streamsize(pixels.size()));
    int worst = 0;
    uint8_t want[3] = {expected.r, expected.g, expected.b};
    for (size_t i = 0; i < pixels.size(); ++i)
        worst = std::max(worst, std::abs(int(pixels[i]) - int(want[i % 3])));
    INFO(file << " first pixel " << int(pixels[0]) << "," << int(pixels[1]) << "," << int(pixels[2]));
    REQUIRE(worst <= 1);
}

VkClearColorValue Bytes(Rgb c) {
    VkClearColorValue v{};
    v.float32[0] = c.r / 255.0f;
    v.float32[1] = c.g / 255.0f;
    v.float32[2] = c.b / 255.0f;
    v.float32[3] = 1.0f;
    return v;
}

glm::vec3 ToGlm(const XrVector3f& v) { return {v.x, v.y, v.z}; }
glm::quat ToGlm(const XrQuaternionf& q) { return {q.w, q.x, q.y, q.z}; }

void RequireNoValidationErrors(const XrEnvironment& env) {
    auto errors = env.ValidationErrors();
    for (const auto& e : errors) WARN(e);
    REQUIRE(errors.empty());
    REQUIRE(g_vulkanErrors == 0);
}

#define FOVRT_REQUIRE_VULKAN() \
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device; OpenXR session test not run")

TEST_CASE("the runtime advertises a stereo HMD with enable2, eye gaze and the recommended size",
          "[xr]") {
    {
        XrEnvironment env(Vars{});
        auto extensions = RuntimeExtensions();
        auto has = [&](const char* name) {
            return std::find(extensions.begin(), extensions.end(), name) != extensions.end();
        };
        CHECK(has(XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME));
        CHECK(has(XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME));
        CHECK(has(XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME));
        XrInstance instance = XR_NULL_HANDLE;
        REQUIRE_XR(CreateInstance({XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME,
                                   XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME,
                                   XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME},
                                  &instance));
        // XrTime is CLOCK_MONOTONIC nanoseconds, both ways.
        auto toTime = Proc<PFN_xrConvertTimespecTimeToTimeKHR>(instance, "xrConvertTimespecTimeToTimeKHR");
        auto toTimespec = Proc<PFN_xrConvertTimeToTimespecTimeKHR>(instance, "xrConvertTimeToTimespecTimeKHR");
        timespec ts{12, 345678901};
        XrTime t = 0;
        REQUIRE_XR(toTime(instance, &ts, &t));
        CHECK(t == 12345678901);
        timespec back{};
        REQUIRE_XR(toTimespec(instance, t, &back));
        CHECK((back.tv_sec == 12 && back.tv_nsec == 345678901));
        auto ip = XrInit<XrInstanceProperties>(XR_TYPE_INSTANCE_PROPERTIES);
        REQUIRE_XR(xrGetInstanceProperties(instance, &ip));
        CHECK(std::string(ip.runtimeName) == "fovrt test runtime");
        XrSystemId system = XR_NULL_SYSTEM_ID;
        REQUIRE_XR(GetSystem(instance, &system));
        auto gaze = XrInit<XrSystemEyeGazeInteractionPropertiesEXT>(XR_TYPE_SYSTEM_EYE_GAZE_INTERACTION_PROPERTIES_EXT);
        auto sp = XrInit<XrSystemProperties>(XR_TYPE_SYSTEM_PROPERTIES);
        sp.next = &gaze;
        REQUIRE_XR(xrGetSystemProperties(instance, system, &sp));
        CHECK(gaze.supportsEyeGazeInteraction == XR_TRUE);  // default "off": supported, no data
        uint32_t n = 0;
        std::vector<XrViewConfigurationView> views(2, XrInit<XrViewConfigurationView>(XR_TYPE_VIEW_CONFIGURATION_VIEW));
        REQUIRE_XR(xrEnumerateViewConfigurationViews(
            instance, system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 2, &n, views.data()));
        REQUIRE(n == 2);
        for (const auto& v : views) {
            CHECK(v.recommendedImageRectWidth == 320);
            CHECK(v.recommendedImageRectHeight == 240);
        }
        XrEnvironmentBlendMode mode{};
        REQUIRE_XR(xrEnumerateEnvironmentBlendModes(
            instance, system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 1, &n, &mode));
        CHECK(mode == XR_ENVIRONMENT_BLEND_MODE_OPAQUE);
        char name[XR_MAX_RESULT_STRING_SIZE];
        REQUIRE_XR(xrResultToString(instance, XR_ERROR_FORM_FACTOR_UNAVAILABLE, name));
        CHECK(std::string(name) == "XR_ERROR_FORM_FACTOR_UNAVAILABLE");
        PFN_xrVoidFunction missing = nullptr;
        CHECK(xrGetInstanceProcAddr(instance, "xrFovrtNoSuchFunction", &missing) ==
              XR_ERROR_FUNCTION_UNSUPPORTED);
        CHECK(missing == nullptr);
        REQUIRE_XR(xrDestroyInstance(instance));
        RequireNoValidationErrors(env);
    }
    {
        XrEnvironment env(Vars{{"FOVRT_TEST_XR_SIZE", "200x100"}, {"FOVRT_TEST_XR_GAZE", "unsupported"}});
        XrInstance instance = XR_NULL_HANDLE;
        REQUIRE_XR(CreateInstance({XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME}, &instance));
        XrSystemId system = XR_NULL_SYSTEM_ID;
        REQUIRE_XR(GetSystem(instance, &system));
        auto gaze = XrInit<XrSystemEyeGazeInteractionPropertiesEXT>(XR_TYPE_SYSTEM_EYE_GAZE_INTERACTION_PROPERTIES_EXT);
        auto sp = XrInit<XrSystemProperties>(XR_TYPE_SYSTEM_PROPERTIES);
        sp.next = &gaze;
        REQUIRE_XR(xrGetSystemProperties(instance, system, &sp));
        CHECK(gaze.supportsEyeGazeInteraction == XR_FALSE);
        uint32_t n = 0;
        std::vector<XrViewConfigurationView> views(2, XrInit<XrViewConfigurationView>(XR_TYPE_VIEW_CONFIGURATION_VIEW));
        REQUIRE_XR(xrEnumerateViewConfigurationViews(
            instance, system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 2, &n, views.data()));
        CHECK(views[0].recommendedImageRectWidth == 200);
        CHECK(views[1].recommendedImageRectHeight == 100);
        REQUIRE_XR(xrDestroyInstance(instance));
        RequireNoValidationErrors(env);
    }
}

TEST_CASE("each failure variable gives its documented XrResult", "[xr]") {
    {
        XrEnvironment env(Vars{{"FOVRT_TEST_XR_NO_ENABLE2", "1"}});
        auto extensions = RuntimeExtensions();
        CHECK(std::find(extensions.begin(), extensions.end(),
                        XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME) == extensions.end());
        XrInstance instance = XR_NULL_HANDLE;
        CHECK(CreateInstance({XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME}, &instance) ==
              XR_ERROR_EXTENSION_NOT_PRESENT);
    }
    for (auto [variable, expected] :
         {std::pair{"FOVRT_TEST_XR_NO_HMD", XR_ERROR_FORM_FACTOR_UNAVAILABLE},
          std::pair{"FOVRT_TEST_XR_FORM_FACTOR_UNSUPPORTED", XR_ERROR_FORM_FACTOR_UNSUPPORTED}}) {
        INFO(variable);
        XrEnvironment env(Vars{{variable, "1"}});
        XrInstance instance = XR_NULL_HANDLE;
        REQUIRE_XR(CreateInstance({XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME}, &instance));
        XrSystemId system = XR_NULL_SYSTEM_ID;
        CHECK(GetSystem(instance, &system) == expected);
        REQUIRE_XR(xrDestroyInstance(instance));
        RequireNoValidationErrors(env);
    }
    {
        XrEnvironment env(Vars{{"FOVRT_TEST_XR_SIZE", "wide"}});  // malformed: the instance refuses
        XrInstance instance = XR_NULL_HANDLE;
        CHECK(CreateInstance({}, &instance) == XR_ERROR_INITIALIZATION_FAILED);
    }
    {
        // A runtime that is not there at all: the loader's own error.
        XrEnvironment env(Vars{});
        ::setenv("XR_RUNTIME_JSON", "/nonexistent/runtime.json", 1);
        XrInstance instance = XR_NULL_HANDLE;
        CHECK(XR_FAILED(CreateInstance({}, &instance)));
    }
}

TEST_CASE("a session runs IDLE to EXITING and the runtime reads back each eye's image", "[xr][vulkan]") {
    FOVRT_REQUIRE_VULKAN();
    fs::path dump = ScratchDir("fovrt-xr-runtime") / "session";
    XrEnvironment env(Vars{{"FOVRT_TEST_XR_DUMP", dump.string()}, {"FOVRT_TEST_XR_SIZE", "96x64"}});
    Client c;
    c.Create();
    REQUIRE_XR(c.CreateSession());
    c.CreateGazeAction();
    c.CreateSwapchains(VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_UNORM);
    REQUIRE(c.width == 96);
    // Suggestions end with the attach.
    XrActionSuggestedBinding late{c.gazeAction, c.Path("/user/eyes_ext/input/gaze_ext/pose")};
    auto suggestion =
        XrInit<XrInteractionProfileSuggestedBinding>(XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING);
    suggestion.interactionProfile = c.Path("/interaction_profiles/ext/eye_gaze_interaction");
    suggestion.countSuggestedBindings = 1;
    suggestion.suggestedBindings = &late;
    CHECK(xrSuggestInteractionProfileBindings(c.instance, &suggestion) ==
          XR_ERROR_ACTIONSETS_ALREADY_ATTACHED);
    REQUIRE(c.height == 64);
    const Rgb left{51, 102, 153}, right{204, 26, 77};
    c.eyes[0].clear = Bytes(left);
    c.eyes[1].clear = Bytes(right);

    c.RunUntil([&] { return c.State() == XR_SESSION_STATE_FOCUSED; });
    CHECK(c.profileChangedSeen);
    for (int i = 0; i < 4; ++i) {
        XrFrameState frame = c.Frame();
        CHECK(frame.shouldRender);
        // Gaze "off" (the default): supported but never active; its space is not located.
        const XrActionStatePose pose = c.SyncGazePose();
        CHECK(pose.isActive == XR_FALSE);
        auto location = XrInit<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
        REQUIRE_XR(xrLocateSpace(c.gazeSpace, c.view, frame.predictedDisplayTime, &location));
        CHECK(location.locationFlags == 0);
    }
    REQUIRE_XR(xrRequestExitSession(c.session));
    c.RunUntil([&] { return c.exitingSeen; });

    const std::vector<XrSessionState> expected = {
        XR_SESSION_STATE_IDLE,    XR_SESSION_STATE_READY,        XR_SESSION_STATE_SYNCHRONIZED,
        XR_SESSION_STATE_VISIBLE, XR_SESSION_STATE_FOCUSED,      XR_SESSION_STATE_VISIBLE,
        XR_SESSION_STATE_SYNCHRONIZED, XR_SESSION_STATE_STOPPING, XR_SESSION_STATE_IDLE,
        XR_SESSION_STATE_EXITING};
    CHECK(c.states == expected);
    CHECK(ReadLines(dump / "states.txt") ==
          std::vector<std::string>{"XR_SESSION_STATE_IDLE", "XR_SESSION_STATE_READY",
                                   "XR_SESSION_STATE_SYNCHRONIZED", "XR_SESSION_STATE_VISIBLE",
                                   "XR_SESSION_STATE_FOCUSED", "XR_SESSION_STATE_VISIBLE",
                                   "XR_SESSION_STATE_SYNCHRONIZED", "XR_SESSION_STATE_STOPPING",
                                   "XR_SESSION_STATE_IDLE", "XR_SESSION_STATE_EXITING"});

    // The dump: one line per xrEndFrame; rendered frames carry two views and their read-back.
    auto frames = ReadFrames(dump);
    REQUIRE(frames.size() >= 6);
    int rendered = 0;
    for (size_t i = 0; i < frames.size(); ++i) {
        const auto& f = frames[i];
        CHECK(f["frame"] == i);
        if (f["layerCount"] == 0) continue;
        ++rendered;
        REQUIRE(f["views"].size() == 2);
        for (int e = 0; e < 2; ++e) {
            const auto& v = f["views"][e];
            CHECK(v["swapchainSize"] == nlohmann::json({96, 64}));
            CHECK(v["imageRect"] == nlohmann::json({0, 0, 96, 64}));
            CHECK(v["format"] == (e == 0 ? "VK_FORMAT_R8G8B8A8_UNORM" : "VK_FORMAT_B8G8R8A8_UNORM"));
            RequireUniformPpm(dump / v["ppm"].get<std::string>(), 96, 64, e == 0 ? left : right);
        }
        CHECK(f["gaze"].is_null());
    }
    CHECK(rendered == int(c.locatedViews.size()));

    // Views: the eyes are the IPD apart, FOVs asymmetric and mirrored, poses move over frames.
    REQUIRE(c.locatedViews.size() >= 4);
    for (const auto& views : c.locatedViews) {
        float ipd = glm::distance(ToGlm(views[0].pose.position), ToGlm(views[1].pose.position));
        CHECK(ipd == Approx(0.063f).margin(1e-5));
        CHECK(views[0].fov.angleLeft == Approx(-0.95f));
        CHECK(views[0].fov.angleRight == Approx(0.80f));
        CHECK(views[0].fov.angleUp == Approx(0.85f));
        CHECK(views[0].fov.angleDown == Approx(-0.90f));
        CHECK(views[1].fov.angleLeft == Approx(-views[0].fov.angleRight));
        CHECK(views[1].fov.angleRight == Approx(-views[0].fov.angleLeft));
        // The left eye is on the head's -x side.
        glm::vec3 leftToRight = ToGlm(views[1].pose.position) - ToGlm(views[0].pose.position);
        glm::vec3 headX = ToGlm(views[0].pose.orientation) * glm::vec3(1, 0, 0);
        CHECK(glm::dot(leftToRight, headX) == Approx(0.063f).margin(1e-4));
    }
    glm::vec3 first = ToGlm(c.locatedViews.front()[0].pose.position);
    glm::vec3 last = ToGlm(c.locatedViews.back()[0].pose.position);
    CHECK(glm::distance(first, last) > 1e-5f);

    c.Destroy();
    RequireNoValidationErrors(env);
}

// Runs a gaze-on session to FOCUSED and checks the located gaze against the script for a few frames.
void CheckGazeSession(const std::map<std::string, std::string>& variables,
                      glm::vec3 (*expectedAt)(XrTime)) {
    fs::path dump = ScratchDir("fovrt-xr-runtime") / ("gaze" + std::to_string(std::rand()));
    auto vars = variables;
    vars["FOVRT_TEST_XR_GAZE"] = "on";
    vars["FOVRT_TEST_XR_SIZE"] = "64x48";
    vars["FOVRT_TEST_XR_DUMP"] = dump.string();
    XrEnvironment env(vars);
    Client c;
    c.Create();
    REQUIRE_XR(c.CreateSession());
    c.CreateGazeAction();
    c.CreateSwapchains(VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT);
    const Rgb grey{128, 128, 128};  // 0.5 in half float reads back as round(127.5) = 128
    c.eyes[0].clear = {{0.5f, 0.5f, 0.5f, 1.0f}};
    c.eyes[1].clear = {{0.5f, 0.5f, 0.5f, 1.0f}};
    c.RunUntil([&] { return c.State() == XR_SESSION_STATE_FOCUSED; });

    auto profile = XrInit<XrInteractionProfileState>(XR_TYPE_INTERACTION_PROFILE_STATE);
    REQUIRE_XR(xrGetCurrentInteractionProfile(c.session, c.Path("/user/eyes_ext"), &profile));
    CHECK(profile.interactionProfile == c.Path("/interaction_profiles/ext/eye_gaze_interaction"));
    for (int i = 0; i < 4; ++i) {
        XrFrameState frame = c.Frame();
        const XrActionStatePose pose = c.SyncGazePose();
        REQUIRE(pose.isActive == XR_TRUE);
        auto sample = XrInit<XrEyeGazeSampleTimeEXT>(XR_TYPE_EYE_GAZE_SAMPLE_TIME_EXT);
        auto location = XrInit<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
        location.next = &sample;
        REQUIRE_XR(xrLocateSpace(c.gazeSpace, c.view, frame.predictedDisplayTime, &location));
        REQUIRE((location.locationFlags & XR_SPACE_LOCATION_ORIENTATION_VALID_BIT) != 0);
        REQUIRE((location.locationFlags & XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT) != 0);
        REQUIRE(sample.time > 0);
        CHECK(sample.time <= frame.predictedDisplayTime);
        glm::vec3 direction = ToGlm(location.pose.orientation) * glm::vec3(0, 0, -1);
        glm::vec3 expected = expectedAt(sample.time);
        INFO("located " << direction.x << "," << direction.y << "," << direction.z << " expected "
                        << expected.x << "," << expected.y << "," << expected.z);
        CHECK(glm::distance(direction, expected) < 1e-4f);
        CHECK(glm::length(ToGlm(location.pose.position)) < 1e-5f);  // gaze origin: the view origin
        // Within 15 degrees of the view axis.
        CHECK(-direction.z > std::cos(15.0f * 3.14159265f / 180.0f));
    }
    REQUIRE_XR(xrRequestExitSession(c.session));
    c.RunUntil([&] { return c.exitingSeen; });
    auto frames = ReadFrames(dump);
    bool any = false;
    for (const auto& f : frames) {
        REQUIRE(f["gaze"].is_array());
        glm::vec3 g(f["gaze"][0].get<float>(), f["gaze"][1].get<float>(), f["gaze"][2].get<float>());
        CHECK(glm::distance(g, expectedAt(f["displayTime"].get<XrTime>())) < 1e-4f);
        for (const auto& v : f["views"]) {
            RequireUniformPpm(dump / v["ppm"].get<std::string>(), 64, 48, grey);
            any = true;
        }
    }
    CHECK(any);
    c.Destroy();
    RequireNoValidationErrors(env);
}

TEST_CASE("gaze on: the gaze action is active and located where the script says", "[xr][vulkan]") {
    FOVRT_REQUIRE_VULKAN();
    SECTION("scripted Lissajous") {
        CheckGazeSession({}, [](XrTime t) { return xrrt::ScriptedGaze(t); });
    }
    SECTION("fixed tangent-space gaze") {
        CheckGazeSession({{"FOVRT_TEST_XR_GAZE_FIXED", "0.2,-0.1"}},
                         [](XrTime) { return xrrt::GazeFromTangent(0.2f, -0.1f); });
    }
}

TEST_CASE("the runtime ends, loses and drops sessions when told to", "[xr][vulkan]") {
    FOVRT_REQUIRE_VULKAN();
    SECTION("FOVRT_TEST_XR_EXIT_AFTER: the user quits after N frames") {
        XrEnvironment env(Vars{{"FOVRT_TEST_XR_EXIT_AFTER", "6"}, {"FOVRT_TEST_XR_SIZE", "32x32"},
                               {"FOVRT_TEST_XR_HZ", "120"}});
        Client c;
        c.StartWithSwapchains();
        c.RunUntil([&] { return c.exitingSeen; });
        CHECK(c.states.back() == XR_SESSION_STATE_EXITING);
        CHECK(std::count(c.states.begin(), c.states.end(), XR_SESSION_STATE_STOPPING) == 1);
        CHECK(c.predictedTimes.size() == 6);
        // The display clock: 120 Hz, predicted times on one vsync grid, strictly increasing.
        CHECK(c.period == 8333333);
        for (size_t i = 1; i < c.predictedTimes.size(); ++i) {
            XrDuration step = c.predictedTimes[i] - c.predictedTimes[i - 1];
            CHECK(step > 0);
            CHECK(step % c.period == 0);
        }
        c.Destroy();
        RequireNoValidationErrors(env);
    }
    SECTION("FOVRT_TEST_XR_LOSS_AFTER: LOSS_PENDING, then the session is lost") {
        XrEnvironment env(Vars{{"FOVRT_TEST_XR_LOSS_AFTER", "5"}, {"FOVRT_TEST_XR_SIZE", "32x32"}});
        Client c;
        c.StartWithSwapchains();
        auto frame = XrInit<XrFrameState>(XR_TYPE_FRAME_STATE);
        int ended = 0;
        for (int i = 0; i < 50 && c.State() != XR_SESSION_STATE_LOSS_PENDING; ++i) {
            // Poll only after the frame so the pending-loss success code can be seen first.
            if (c.Running() && i > 0) {
                XrResult r = xrWaitFrame(c.session, nullptr, &frame);
                REQUIRE((r == XR_SUCCESS || r == XR_SESSION_LOSS_PENDING));
                if (r == XR_SESSION_LOSS_PENDING) {
                    CHECK(ended >= 5);
                }
                REQUIRE(XR_SUCCEEDED(xrBeginFrame(c.session, nullptr)));
                auto end = XrInit<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
                end.displayTime = frame.predictedDisplayTime;
                end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
                REQUIRE(XR_SUCCEEDED(xrEndFrame(c.session, &end)));
                ++ended;
            }
            c.PollEvents();
        }
        REQUIRE(c.State() == XR_SESSION_STATE_LOSS_PENDING);
        CHECK(xrWaitFrame(c.session, nullptr, &frame) == XR_ERROR_SESSION_LOST);
        REQUIRE_XR(xrDestroySession(c.session));
        c.session = XR_NULL_HANDLE;
        for (auto& e : c.eyes) e.swapchain = XR_NULL_HANDLE;  // destroyed with the session
        c.local = c.view = XR_NULL_HANDLE;
        c.Destroy();
        RequireNoValidationErrors(env);
    }
    SECTION("FOVRT_TEST_XR_INSTANCE_LOSS_AFTER: instance loss pending, then lost") {
        XrEnvironment env(Vars{{"FOVRT_TEST_XR_INSTANCE_LOSS_AFTER", "4"}, {"FOVRT_TEST_XR_SIZE", "32x32"}});
        Client c;
        c.StartWithSwapchains();
        c.RunUntil([&] { return c.instanceLossSeen; });
        auto event = XrInit<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
        CHECK(xrPollEvent(c.instance, &event) == XR_ERROR_INSTANCE_LOST);
        auto frame = XrInit<XrFrameState>(XR_TYPE_FRAME_STATE);
        CHECK(xrWaitFrame(c.session, nullptr, &frame) == XR_ERROR_INSTANCE_LOST);
        c.Destroy();  // destroying still works
        RequireNoValidationErrors(env);
    }
}

TEST_CASE("the runtime refuses frame calls out of order and sessions without a binding",
          "[xr][vulkan]") {
    FOVRT_REQUIRE_VULKAN();
    XrEnvironment env(Vars{{"FOVRT_TEST_XR_SIZE", "32x32"}});
    Client c;
    c.Create();
    auto noBinding = XrInit<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
    noBinding.systemId = c.system;
    XrSession session = XR_NULL_HANDLE;
    CHECK(xrCreateSession(c.instance, &noBinding, &session) == XR_ERROR_GRAPHICS_DEVICE_INVALID);
    // Suggested bindings: the gaze profile takes only the gaze pose, khr/simple_controller only its
    // own paths; other vendors' profiles are accepted (applications suggest many).
    auto si = XrInit<XrActionSetCreateInfo>(XR_TYPE_ACTION_SET_CREATE_INFO);
    std::snprintf(si.actionSetName, sizeof si.actionSetName, "bindings");
    std::snprintf(si.localizedActionSetName, sizeof si.localizedActionSetName, "Bindings");
    XrActionSet set = XR_NULL_HANDLE;
    REQUIRE_XR(xrCreateActionSet(c.instance, &si, &set));
    auto ai = XrInit<XrActionCreateInfo>(XR_TYPE_ACTION_CREATE_INFO);
    ai.actionType = XR_ACTION_TYPE_POSE_INPUT;
    std::snprintf(ai.actionName, sizeof ai.actionName, "pose");
    std::snprintf(ai.localizedActionName, sizeof ai.localizedActionName, "Pose");
    XrAction action = XR_NULL_HANDLE;
    REQUIRE_XR(xrCreateAction(set, &ai, &action));
    auto suggest = [&](const char* profile, const char* path) {
        XrActionSuggestedBinding binding{action, c.Path(path)};
        auto info = XrInit<XrInteractionProfileSuggestedBinding>(
            XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING);
        info.interactionProfile = c.Path(profile);
        info.countSuggestedBindings = 1;
        info.suggestedBindings = &binding;
        return xrSuggestInteractionProfileBindings(c.instance, &info);
    };
    CHECK(suggest("/interaction_profiles/ext/eye_gaze_interaction",
                  "/user/eyes_ext/input/gaze_ext/position") == XR_ERROR_PATH_UNSUPPORTED);
    CHECK(suggest("/interaction_profiles/khr/simple_controller",
                  "/user/hand/left/input/trigger/value") == XR_ERROR_PATH_UNSUPPORTED);
    CHECK(suggest("/interaction_profiles/khr/simple_controller", "/user/hand/left/input/aim/pose") ==
          XR_SUCCESS);
    CHECK(suggest("/interaction_profiles/valve/index_controller",
                  "/user/hand/right/input/grip/pose") == XR_SUCCESS);
    CHECK(suggest("/interaction_profiles/ext/eye_gaze_interaction",
                  "/user/eyes_ext/input/gaze_ext/pose") == XR_SUCCESS);
    REQUIRE_XR(xrDestroyActionSet(set));

    REQUIRE_XR(c.CreateSession());
    c.CreateSwapchains(VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM);
    auto frame = XrInit<XrFrameState>(XR_TYPE_FRAME_STATE);
    CHECK(xrWaitFrame(c.session, nullptr, &frame) == XR_ERROR_SESSION_NOT_RUNNING);
    c.PollEvents();  // READY: begins the session
    REQUIRE(c.State() == XR_SESSION_STATE_READY);
    CHECK(xrBeginFrame(c.session, nullptr) == XR_ERROR_CALL_ORDER_INVALID);
    auto end = XrInit<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
    end.displayTime = 1;
    end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
    CHECK(xrEndFrame(c.session, &end) == XR_ERROR_CALL_ORDER_INVALID);
    CHECK(xrEndSession(c.session) == XR_ERROR_SESSION_NOT_STOPPING);
    REQUIRE_XR(xrWaitFrame(c.session, nullptr, &frame));
    REQUIRE_XR(xrBeginFrame(c.session, nullptr));
    CHECK(xrReleaseSwapchainImage(c.eyes[0].swapchain, nullptr) == XR_ERROR_CALL_ORDER_INVALID);
    // A projection layer naming a swapchain that never released an image.
    XrCompositionLayerProjectionView views[2] = {
        XrInit<XrCompositionLayerProjectionView>(XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW),
        XrInit<XrCompositionLayerProjectionView>(XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW)};
    for (auto& v : views) {
        v.pose.orientation.w = 1.0f;
        v.subImage.swapchain = c.eyes[0].swapchain;
        v.subImage.imageRect = {{0, 0}, {32, 32}};
    }
    auto layer = XrInit<XrCompositionLayerProjection>(XR_TYPE_COMPOSITION_LAYER_PROJECTION);
    layer.space = c.local;
    layer.viewCount = 2;
    layer.views = views;
    const XrCompositionLayerBaseHeader* layers[] = {
        reinterpret_cast<const XrCompositionLayerBaseHeader*>(&layer)};
    end.displayTime = frame.predictedDisplayTime;
    end.layerCount = 1;
    end.layers = layers;
    CHECK(xrEndFrame(c.session, &end) == XR_ERROR_LAYER_INVALID);
    c.Destroy();
    // Core validation saw the missing binding too (and nothing else): its report is being read.
    if (HaveCoreValidation()) {
        auto errors = env.ValidationErrors();
        REQUIRE(errors.size() == 1);
        CHECK(errors[0].find("VUID-xrCreateSession-next-parameter") != std::string::npos);
    }
}

}  // namespace
}  // namespace fovrt::test
