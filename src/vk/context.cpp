#include "vk/context.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <optional>

#include "core/error.h"
#include "vk/device_choice.h"
#include "vk/leak_check_pin.h"
#include "vk/shared_buffers.h"
#include "vk/vk_check.h"

namespace fovrt {

struct VulkanContext::State {
    bool owned = false;  // instance/device created here (destroyed here)
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    VkCommandPool commandPool = VK_NULL_HANDLE;
    std::string deviceName;
    bool cpu = false;
    bool storage16 = false;
    bool timestamps = false;
    double timestampPeriodNs = 1.0;
    bool validation = false;
    std::atomic<uint32_t> errors{0};
    std::atomic<uint32_t> warnings{0};
    mutable std::mutex queueMutex;
    VulkanAllocator allocator;
    std::mutex sharedMutex;
    std::weak_ptr<SharedBuffers> shared;  // held by its users, so it dies with the last of them

    ~State() {
        if (device != VK_NULL_HANDLE) vkDeviceWaitIdle(device);
        if (commandPool != VK_NULL_HANDLE) vkDestroyCommandPool(device, commandPool, nullptr);
        if (!owned) return;
        if (device != VK_NULL_HANDLE) vkDestroyDevice(device, nullptr);
        if (messenger != VK_NULL_HANDLE) {
            auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
            if (destroy) destroy(instance, messenger, nullptr);
        }
        KeepLoadedLibrariesForLeakCheck();  // before the loader unloads the driver and layers
        if (instance != VK_NULL_HANDLE) vkDestroyInstance(instance, nullptr);
    }
};

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL DebugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data,
                                             void* user) {
    auto* state = static_cast<VulkanContext::State*>(user);
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        state->errors++;
        std::fprintf(stderr, "vulkan validation error: %s\n", data->pMessage);
    } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        state->warnings++;
        std::fprintf(stderr, "vulkan validation warning: %s\n", data->pMessage);
    }
    return VK_FALSE;
}

const char* TypeName(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
        default: return "other";
    }
}

bool LayerAvailable(const char* name) {
    uint32_t count = 0;
    if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
    std::vector<VkLayerProperties> layers(count);
    if (vkEnumerateInstanceLayerProperties(&count, layers.data()) != VK_SUCCESS) return false;
    for (const auto& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

bool WantValidation(Validation v) {
    if (v == Validation::On) return true;
    if (v == Validation::Off) return false;
    if (const char* env = std::getenv("FOVRT_VK_VALIDATION")) return std::strcmp(env, "0") != 0;
#ifndef NDEBUG
    return true;
#else
    return false;
#endif
}

std::vector<VkPhysicalDevice> EnumerateDevices(VkInstance instance) {
    uint32_t count = 0;
    FOVRT_VK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    if (count) FOVRT_VK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    return devices;
}

using QueueFamilyFilter = std::function<bool(VkPhysicalDevice, uint32_t)>;

std::optional<uint32_t> ComputeQueueFamily(VkPhysicalDevice pd, const QueueFamilyFilter& accepts = {}) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, families.data());
    for (uint32_t i = 0; i < count; ++i)
        if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && (!accepts || accepts(pd, i))) return i;
    return std::nullopt;
}

VkInstance CreateBareInstance() {
    auto app = VkInit<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "fovrt";
    app.apiVersion = VK_API_VERSION_1_1;
    auto info = VkInit<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    info.pApplicationInfo = &app;
    VkInstance instance = VK_NULL_HANDLE;
    VkResult r = vkCreateInstance(&info, nullptr, &instance);
    if (r != VK_SUCCESS) return VK_NULL_HANDLE;
    return instance;
}

// Fills the device-dependent fields of a state from its physical device and queue family.
void DescribeDevice(VulkanContext::State& s) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(s.physicalDevice, &props);
    s.deviceName = props.deviceName;
    s.cpu = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    s.timestampPeriodNs = props.limits.timestampPeriod;
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(s.physicalDevice, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(s.physicalDevice, &count, families.data());
    s.timestamps = s.queueFamily < count && families[s.queueFamily].timestampValidBits > 0 &&
                   props.limits.timestampPeriod > 0.0f;
}

void CreateCommandPool(VulkanContext::State& s) {
    auto info = VkInit<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    info.queueFamilyIndex = s.queueFamily;
    FOVRT_VK(vkCreateCommandPool(s.device, &info, nullptr, &s.commandPool));
}

}  // namespace

std::vector<VulkanDeviceInfo> VulkanContext::ListDevices() {
    std::vector<VulkanDeviceInfo> out;
    VkInstance instance = CreateBareInstance();
    if (!instance) return out;
    uint32_t count = 0;
    if (vkEnumeratePhysicalDevices(instance, &count, nullptr) == VK_SUCCESS && count) {
        std::vector<VkPhysicalDevice> devices(count);
        vkEnumeratePhysicalDevices(instance, &count, devices.data());
        for (uint32_t i = 0; i < count; ++i) {
            VkPhysicalDeviceProperties props;
            vkGetPhysicalDeviceProperties(devices[i], &props);
            auto storage16 = VkInit<VkPhysicalDevice16BitStorageFeatures>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_16BIT_STORAGE_FEATURES);
            auto features2 = VkInit<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
            features2.pNext = &storage16;
            vkGetPhysicalDeviceFeatures2(devices[i], &features2);
            out.push_back({i, props.deviceName, TypeName(props.deviceType), ComputeQueueFamily(devices[i]).has_value(),
                           storage16.storageBuffer16BitAccess == VK_TRUE});
        }
    }
    vkDestroyInstance(instance, nullptr);
    return out;
}

bool VulkanContext::Available() {
    static std::once_flag once;
    static bool available = false;
    std::call_once(once, [] {
        for (const auto& d : ListDevices()) {
            (void)d;
            available = true;
        }
    });
    return available;
}

VulkanContext VulkanContext::Create(const VulkanContextOptions& options) {
    auto s = std::make_unique<State>();
    s->owned = true;
    bool validation = WantValidation(options.validation);
    if (validation && !LayerAvailable("VK_LAYER_KHRONOS_validation")) {
        // CI installs the layer: there a check for zero validation messages must not pass
        // because nothing validated (docs/testing.md, FOVRT_REQUIRE_ALL).
        const char* requireAll = std::getenv("FOVRT_REQUIRE_ALL");
        if (requireAll && std::strcmp(requireAll, "1") == 0)
            Fail("VK_LAYER_KHRONOS_validation is not installed, and FOVRT_REQUIRE_ALL=1 makes "
                 "running without the validation that was asked for an error (apt-get install "
                 "vulkan-validationlayers)");
        if (!options.quiet)
            std::fprintf(stderr, "fovrt: notice: VK_LAYER_KHRONOS_validation is not installed; "
                                 "running without validation\n");
        validation = false;
    }
    s->validation = validation;

    auto app = VkInit<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "fovrt";
    app.apiVersion = VK_API_VERSION_1_1;
    std::vector<const char*> layers, extensions;
    auto debugInfo = VkInit<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    debugInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    debugInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    debugInfo.pfnUserCallback = DebugCallback;
    debugInfo.pUserData = s.get();
    auto info = VkInit<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    info.pApplicationInfo = &app;
    if (validation) {
        layers.push_back("VK_LAYER_KHRONOS_validation");
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        info.pNext = &debugInfo;  // also covers instance creation/destruction
    }
    for (const std::string& e : options.instanceExtensions) extensions.push_back(e.c_str());
    info.enabledLayerCount = uint32_t(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkResult r = VK_SUCCESS;
    if (options.createInstance) {
        s->instance = options.createInstance(info);
    } else {
        r = vkCreateInstance(&info, nullptr, &s->instance);
        if (r != VK_SUCCESS) Fail("no Vulkan instance ({}): is a Vulkan driver installed?", VkResultName(r));
    }
    if (validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(s->instance, "vkCreateDebugUtilsMessengerEXT"));
        if (create) FOVRT_VK(create(s->instance, &debugInfo, nullptr, &s->messenger));
    }

    std::vector<VkPhysicalDevice> devices = EnumerateDevices(s->instance);
    QueueFamilyFilter accepts;
    if (options.queueFamilyAccepts)
        accepts = [&options, instance = s->instance](VkPhysicalDevice pd, uint32_t family) {
            return options.queueFamilyAccepts(instance, pd, family);
        };
    if (devices.empty()) Fail("no Vulkan device found (vkEnumeratePhysicalDevices returned none)");
    std::vector<VulkanDeviceInfo> infos;
    for (uint32_t i = 0; i < devices.size(); ++i) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devices[i], &p);
        infos.push_back({i, p.deviceName, TypeName(p.deviceType), ComputeQueueFamily(devices[i], accepts).has_value()});
    }
    // The one device resolution every command uses, against this instance's devices.
    const DeviceDecision decision = ResolveVulkanDevice(options.device, infos);
    if (!decision.vulkan)
        Fail("denoise.device = \"{}\": {}", options.device,
             decision.notice.empty() ? "the C++ reference, which needs no Vulkan context"
                                     : "no Vulkan device with a compute queue");
    uint32_t pick = decision.index;
    if (options.pickPhysicalDevice) {
        const VkPhysicalDevice chosen = options.pickPhysicalDevice(s->instance);
        const auto it = std::find(devices.begin(), devices.end(), chosen);
        if (it == devices.end()) Fail("the physical device chosen for the context is not one of the instance's");
        const uint32_t index = uint32_t(it - devices.begin());
        if (options.device != "auto" && options.device != "vulkan" && index != pick)
            std::fprintf(stderr, "fovrt: warning: denoise.device = \"%s\" ignored: the device that drives the "
                                 "headset is %u (%s)\n", options.device.c_str(), index, infos[index].name.c_str());
        pick = index;
    }
    s->physicalDevice = devices[pick];
    auto family = ComputeQueueFamily(s->physicalDevice, accepts);
    if (!family)
        Fail("Vulkan device {} has no compute queue{}", pick,
             accepts ? " that can also present to the window" : "");
    s->queueFamily = *family;

    // 16-bit storage for fp16 histories, when the device has it.
    auto storage16 = VkInit<VkPhysicalDevice16BitStorageFeatures>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_16BIT_STORAGE_FEATURES);
    auto features2 = VkInit<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
    features2.pNext = &storage16;
    vkGetPhysicalDeviceFeatures2(s->physicalDevice, &features2);
    auto enable16 = VkInit<VkPhysicalDevice16BitStorageFeatures>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_16BIT_STORAGE_FEATURES);
    enable16.storageBuffer16BitAccess = storage16.storageBuffer16BitAccess;
    s->storage16 = storage16.storageBuffer16BitAccess == VK_TRUE;

    float priority = 1.0f;
    auto queueInfo = VkInit<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queueInfo.queueFamilyIndex = s->queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    auto deviceInfo = VkInit<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    deviceInfo.pNext = &enable16;
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    std::vector<const char*> deviceExtensions;
    for (const std::string& e : options.deviceExtensions) deviceExtensions.push_back(e.c_str());
    deviceInfo.enabledExtensionCount = uint32_t(deviceExtensions.size());
    deviceInfo.ppEnabledExtensionNames = deviceExtensions.data();
    if (options.createDevice) {
        s->device = options.createDevice(s->physicalDevice, deviceInfo);
    } else {
        r = vkCreateDevice(s->physicalDevice, &deviceInfo, nullptr, &s->device);
        if (r != VK_SUCCESS) Fail("cannot create Vulkan device {}: {}", pick, VkResultName(r));
    }
    vkGetDeviceQueue(s->device, s->queueFamily, 0, &s->queue);
    DescribeDevice(*s);
    CreateCommandPool(*s);
    s->allocator.Init(s->physicalDevice, s->device);
    return VulkanContext(std::move(s));
}

VulkanContext VulkanContext::Wrap(const ExternalVulkan& e) {
    if (!e.instance || !e.physicalDevice || !e.device || !e.queue)
        Fail("VulkanContext::Wrap: instance, physical device, device and queue are all required");
    auto s = std::make_unique<State>();
    s->owned = false;
    s->instance = e.instance;
    s->physicalDevice = e.physicalDevice;
    s->device = e.device;
    s->queue = e.queue;
    s->queueFamily = e.queueFamily;
    s->storage16 = e.storageBuffer16BitEnabled;
    DescribeDevice(*s);
    CreateCommandPool(*s);
    s->allocator.Init(s->physicalDevice, s->device);
    return VulkanContext(std::move(s));
}

VulkanContext::VulkanContext(std::unique_ptr<State> state) : s_(std::move(state)) {}
VulkanContext::VulkanContext(VulkanContext&&) noexcept = default;
VulkanContext& VulkanContext::operator=(VulkanContext&&) noexcept = default;
VulkanContext::~VulkanContext() = default;

VkInstance VulkanContext::instance() const { return s_->instance; }
VkPhysicalDevice VulkanContext::physicalDevice() const { return s_->physicalDevice; }
VkDevice VulkanContext::device() const { return s_->device; }
VkQueue VulkanContext::queue() const { return s_->queue; }
uint32_t VulkanContext::queueFamily() const { return s_->queueFamily; }
VkCommandPool VulkanContext::commandPool() const { return s_->commandPool; }
std::unique_lock<std::mutex> VulkanContext::LockQueue() const {
    return std::unique_lock<std::mutex>(s_->queueMutex);
}
const std::string& VulkanContext::deviceName() const { return s_->deviceName; }
bool VulkanContext::isCpuDevice() const { return s_->cpu; }
bool VulkanContext::supports16BitStorage() const { return s_->storage16; }
bool VulkanContext::supportsTimestamps() const { return s_->timestamps; }
double VulkanContext::timestampPeriodNs() const { return s_->timestampPeriodNs; }
bool VulkanContext::validationEnabled() const { return s_->validation; }
uint32_t VulkanContext::validationErrors() const { return s_->errors; }
uint32_t VulkanContext::validationWarnings() const { return s_->warnings; }
VulkanAllocator& VulkanContext::allocator() { return s_->allocator; }
const VulkanAllocator& VulkanContext::allocator() const { return s_->allocator; }

std::shared_ptr<SharedBuffers> VulkanContext::SharedDeviceBuffers() {
    std::lock_guard<std::mutex> lock(s_->sharedMutex);
    std::shared_ptr<SharedBuffers> shared = s_->shared.lock();
    if (!shared) {
        shared = std::make_shared<SharedBuffers>(s_->allocator);
        s_->shared = shared;
    }
    return shared;
}

}  // namespace fovrt
