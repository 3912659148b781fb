// fovrt's test OpenXR runtime: the objects behind the handles and the helpers every entry point
// shares. One process-wide registry (Runtime) holds every live object so a handle is checked
// before it is dereferenced; one mutex serialises the API (xrWaitFrame sleeps outside it).
// Reads the FOVRT_TEST_XR_* environment at xrCreateInstance (README.md lists the variables).
#pragma once

#define XR_NO_PROTOTYPES  // the loader exports the xr* symbols; this library must not
#define XR_USE_GRAPHICS_API_VULKAN
#define XR_USE_TIMESPEC
#include <time.h>
#include <vulkan/vulkan.h>
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <cstdint>
#include <cstring>
#include <deque>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "motion.h"

namespace fovrt::xrrt {

constexpr XrSystemId kSystemId = 1;
constexpr uint32_t kViewCount = 2;
constexpr uint32_t kMaxImageSize = 2048;
constexpr uint32_t kMaxLayerCount = 16;
constexpr uint32_t kSwapchainImageCount = 3;
constexpr const char* kEyeGazeProfile = "/interaction_profiles/ext/eye_gaze_interaction";
constexpr const char* kEyeGazePosePath = "/user/eyes_ext/input/gaze_ext/pose";
constexpr const char* kEyesUserPath = "/user/eyes_ext";

enum class GazeMode { Off, On, Unsupported };

// The FOVRT_TEST_XR_* environment, read once per xrCreateInstance.
struct Config {
    uint32_t width = 320, height = 240;  // recommended per-eye size
    double hz = 90.0;
    GazeMode gaze = GazeMode::Off;
    bool gazeFixed = false;
    float gazeTx = 0.0f, gazeTy = 0.0f;
    bool noEnable2 = false;
    bool noHmd = false;
    bool formFactorUnsupported = false;
    int64_t exitAfter = -1, lossAfter = -1, instanceLossAfter = -1;  // frames; -1 = never
    std::string dumpDir;  // empty = no dump

    // False with *error naming the variable and its value when one is malformed.
    static bool FromEnvironment(Config* config, std::string* error);
};

struct Session;
struct Action;
struct ActionSet;

struct Instance {
    Config config;
    std::set<std::string> extensions;  // enabled by the application
    std::vector<std::string> paths;    // XrPath n is paths[n - 1]
    std::map<std::string, XrPath> pathIds;
    struct Event {
        XrEventDataBuffer data;
        size_t size;
    };
    std::deque<Event> events;
    bool systemQueried = false;
    bool graphicsRequirementsQueried = false;
    PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;  // the app's, from enable2
    VkInstance vkInstance = VK_NULL_HANDLE;                      // created by enable2
    Session* session = nullptr;
    std::vector<ActionSet*> actionSets;
    // Suggested bindings per interaction profile: (action, binding path) pairs, last call wins.
    std::map<XrPath, std::vector<std::pair<Action*, XrPath>>> suggested;
    bool lossEventQueued = false;  // FOVRT_TEST_XR_INSTANCE_LOSS_AFTER reached
    bool lost = false;             // the loss event was delivered: every call fails from now on

    bool Enabled(const char* extension) const { return extensions.count(extension) != 0; }
};

struct Swapchain;
struct Space;

struct Session {
    Instance* instance = nullptr;
    // The application's Vulkan objects (XrGraphicsBindingVulkan2KHR) and the runtime's own
    // command pool, fence and read-back buffer on that device.
    VkInstance vkInstance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t queueFamily = 0, queueIndex = 0;
    VkQueue queue = VK_NULL_HANDLE;
    VkCommandPool commandPool = VK_NULL_HANDLE;
    VkCommandBuffer commandBuffer = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    VkBuffer readback = VK_NULL_HANDLE;
    VkDeviceMemory readbackMemory = VK_NULL_HANDLE;
    VkDeviceSize readbackSize = 0;
    void* readbackMapped = nullptr;

    XrSessionState state = XR_SESSION_STATE_IDLE;
    bool running = false;        // between xrBeginSession and xrEndSession
    bool exiting = false;        // xrRequestExitSession or FOVRT_TEST_XR_EXIT_AFTER
    bool lossPending = false;    // FOVRT_TEST_XR_LOSS_AFTER reached: calls return XR_SESSION_LOSS_PENDING
    bool lost = false;           // the LOSS_PENDING event was delivered: XR_ERROR_SESSION_LOST

    // Frame timing: display slots on a fixed grid from xrBeginSession (never drifts).
    XrTime slotOrigin = 0;
    int64_t lastSlot = -1;
    uint32_t framesWaited = 0;  // xrWaitFrame calls not yet matched by xrBeginFrame
    bool frameBegun = false;
    uint64_t framesEnded = 0;

    std::vector<Swapchain*> swapchains;
    std::vector<Space*> spaces;
    std::set<Action*> activeActions;  // pose actions active since the last xrSyncActions
    bool actionSetsAttached = false;
};

struct Swapchain {
    Session* session = nullptr;
    XrSwapchainCreateInfo info{};
    VkFormat format = VK_FORMAT_UNDEFINED;
    struct Image {
        VkImage image = VK_NULL_HANDLE;
        VkDeviceMemory memory = VK_NULL_HANDLE;
        bool initialised = false;  // moved to COLOR_ATTACHMENT_OPTIMAL (at its first acquire)
    };
    std::vector<Image> images;
    struct Acquired {
        uint32_t index;
        bool waited;
    };
    std::deque<Acquired> acquired;  // oldest first
    uint32_t nextIndex = 0;
    int32_t lastReleased = -1;
    bool staticImageAcquired = false;
};

struct Space {
    Session* session = nullptr;
    bool isAction = false;
    XrReferenceSpaceType referenceType = XR_REFERENCE_SPACE_TYPE_LOCAL;
    Action* action = nullptr;
    Pose offset;  // poseInReferenceSpace / poseInActionSpace
};

struct ActionSet {
    Instance* instance = nullptr;
    std::string name;
    std::vector<Action*> actions;
    bool attached = false;
};

struct Action {
    ActionSet* set = nullptr;
    std::string name;
    XrActionType type = XR_ACTION_TYPE_POSE_INPUT;
    std::vector<XrPath> subactionPaths;
};

// Every live object, so that handles can be validated; and the lock the API runs under.
struct Runtime {
    std::mutex mutex;
    std::set<Instance*> instances;
    std::set<Session*> sessions;
    std::set<Swapchain*> swapchains;
    std::set<Space*> spaces;
    std::set<ActionSet*> actionSets;
    std::set<Action*> actions;
};
Runtime& TheRuntime();
inline std::unique_lock<std::mutex> LockApi() { return std::unique_lock(TheRuntime().mutex); }

template <typename Object, typename Handle>
Object* Find(const std::set<Object*>& live, Handle handle) {
    auto* object = reinterpret_cast<Object*>(handle);
    return live.count(object) ? object : nullptr;
}
// An xrDestroy* call: under the API lock, the handle looked up among the live objects of its
// type (XR_ERROR_HANDLE_INVALID when it is not one), then `destroy` frees it.
template <typename Object, typename Handle, typename Destroy>
XrResult DestroyHandle(std::set<Object*>& live, Handle handle, Destroy destroy) {
    auto lock = LockApi();
    Object* object = Find(live, handle);
    if (!object) return XR_ERROR_HANDLE_INVALID;
    destroy(object);
    return XR_SUCCESS;
}
template <typename Handle, typename Object>
Handle ToHandle(Object* object) {
    return reinterpret_cast<Handle>(object);
}

// Handle checks shared by the entry points: XR_ERROR_HANDLE_INVALID, then XR_ERROR_INSTANCE_LOST.
XrResult CheckInstance(XrInstance handle, Instance** out);
XrResult CheckSession(XrSession handle, Session** out);
// CheckSession, then SessionGate: the prologue of every call on a running session (a failure, or
// the result the call returns when it otherwise succeeds).
XrResult CheckSessionAndGate(XrSession handle, Session** out);
// A call on a running session: CheckSessionAndGate, then `body(Session*)`, all under the API lock.
// Returns the prologue's failure, else what body returns with its XR_SUCCESS replaced by the
// gate's result (XR_SESSION_LOSS_PENDING while a loss is queued).
template <typename Body>
XrResult OnRunningSession(XrSession handle, Body&& body) {
    auto lock = LockApi();
    Session* s = nullptr;
    const XrResult gate = CheckSessionAndGate(handle, &s);
    if (XR_FAILED(gate)) return gate;
    const XrResult result = body(s);
    return result == XR_SUCCESS ? gate : result;
}

// XR_ERROR_SYSTEM_INVALID unless id is the system xrGetSystem returned.
XrResult CheckSystem(const Instance& instance, XrSystemId id);
// CheckInstance, then CheckSystem: the prologue of the calls that name a system.
XrResult CheckInstanceSystem(XrInstance handle, XrSystemId id, Instance** out);
// Teardown used by the destroy calls of the owning objects.
void DestroySessionObject(Session* session);
void DestroyActionSetObject(ActionSet* set);

// XR_ERROR_SESSION_LOST once the LOSS_PENDING state was delivered, XR_SESSION_LOSS_PENDING while
// it is queued, else XR_SUCCESS: the result a session function returns when it otherwise succeeds.
XrResult SessionGate(const Session& session);

// The clock: CLOCK_MONOTONIC in nanoseconds.
XrTime Now();

// Paths. PathString returns nullptr for an unknown path.
XrPath InternPath(Instance& instance, const std::string& path);
const std::string* PathString(const Instance& instance, XrPath path);

// Events and session states (each state is also appended to the dump's states.txt).
void PushEvent(Instance& instance, const void* event, size_t size);
void SetSessionState(Session& session, XrSessionState state);
const char* SessionStateName(XrSessionState state);

// Where a space is in STAGE space at a time; valid=false for an inactive action space.
// gazeSampleTime receives the eye-tracker sample time for a gaze action space.
Pose SpaceInStage(const Space& space, XrTime time, bool* valid, XrTime* gazeSampleTime);
// The scripted (or fixed) gaze direction in VIEW space at a time.
glm::vec3 GazeDirection(const Config& config, XrTime time);
bool GazeActionActive(const Session& session, const Action* action);

// Swapchain internals used by the frame loop and session teardown.
void DestroySwapchainObject(Swapchain* swapchain);
// Copies each projection view's released image rect to host memory on the application's queue and,
// with FOVRT_TEST_XR_DUMP, writes the PPMs and the frames.jsonl line.
XrResult ReadBackAndDump(Session& session, const XrFrameEndInfo& info, uint64_t frame);
void DestroyReadback(Session& session);
// Submits one command buffer on the session's queue and waits for it.
XrResult SubmitAndWait(Session& session, VkCommandBuffer commandBuffer);
const char* VkFormatName(VkFormat format);

// Two-call idiom for arrays (XR_ERROR_SIZE_INSUFFICIENT when capacity is short).
template <typename T, typename Fill>
XrResult TwoCall(uint32_t capacity, uint32_t* count, T* out, uint32_t n, Fill fill) {
    if (!count) return XR_ERROR_VALIDATION_FAILURE;
    *count = n;
    if (capacity == 0) return XR_SUCCESS;
    if (capacity < n) return XR_ERROR_SIZE_INSUFFICIENT;
    if (!out) return XR_ERROR_VALIDATION_FAILURE;
    for (uint32_t i = 0; i < n; ++i) fill(out[i], i);
    return XR_SUCCESS;
}
XrResult TwoCallString(uint32_t capacity, uint32_t* count, char* out, const std::string& value);

// Walks an XR next chain for a structure type.
template <typename T>
T* FindInChain(const void* next, XrStructureType type) {
    for (auto* p = static_cast<const XrBaseInStructure*>(next); p; p = p->next)
        if (p->type == type) return reinterpret_cast<T*>(const_cast<XrBaseInStructure*>(p));
    return nullptr;
}

// Zero-initialised structures with their type set (no missing-initializer warnings).
template <typename T>
T XrInit(XrStructureType type) {
    T value{};
    value.type = type;
    return value;
}
template <typename T>
T VkInit(VkStructureType type) {
    T value{};
    value.sType = type;
    return value;
}

bool IsUnitQuaternion(const XrQuaternionf& q);
Pose FromXr(const XrPosef& pose);
XrPosef ToXr(const Pose& pose);

// One line on stderr, prefixed so it is clear the test runtime speaks.
void Log(const std::string& message);

// The entry points, one table per source file; xrGetInstanceProcAddr looks names up in their union.
// extension: the instance extension that must be enabled for the function to resolve, or null.
struct ApiFunction {
    const char* name;
    PFN_xrVoidFunction function;
    const char* extension;
};
using ApiTable = std::vector<ApiFunction>;
void AddInstanceFunctions(ApiTable& table);
void AddVulkanFunctions(ApiTable& table);
void AddSessionFunctions(ApiTable& table);
void AddSpaceFunctions(ApiTable& table);
void AddSwapchainFunctions(ApiTable& table);
void AddActionFunctions(ApiTable& table);
template <typename F>
PFN_xrVoidFunction Fn(F function) {
    return reinterpret_cast<PFN_xrVoidFunction>(function);
}
// A core entry point xr<Name> implemented by the function <Name>.
#define XRRT_CORE(name) ::fovrt::xrrt::ApiFunction{"xr" #name, ::fovrt::xrrt::Fn(&name), nullptr}

}  // namespace fovrt::xrrt

// Checks a VkResult inside an entry point: logs the call and returns XR_ERROR_RUNTIME_FAILURE.
#define XRRT_VK(call)                                                                  \
    do {                                                                               \
        VkResult xrrt_vk_result_ = (call);                                             \
        if (xrrt_vk_result_ != VK_SUCCESS) {                                           \
            ::fovrt::xrrt::Log(std::string(#call) + " failed: VkResult " + std::to_string(xrrt_vk_result_)); \
            return XR_ERROR_RUNTIME_FAILURE;                                           \
        }                                                                              \
    } while (0)
