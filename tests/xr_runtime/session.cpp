// Session: the state machine and the frame loop.
// States: xrCreateSession emits IDLE then READY; xrBeginSession; each xrEndFrame then advances one
// step READY -> SYNCHRONIZED -> VISIBLE -> FOCUSED. An exit (xrRequestExitSession, or
// FOVRT_TEST_XR_EXIT_AFTER frames) steps back down FOCUSED -> VISIBLE -> SYNCHRONIZED -> STOPPING as
// real runtimes do; xrEndSession then emits IDLE, EXITING. LOSS_PENDING and instance loss follow
// FOVRT_TEST_XR_LOSS_AFTER / FOVRT_TEST_XR_INSTANCE_LOSS_AFTER.
// Pacing: display slots lie on a fixed grid from xrBeginSession at FOVRT_TEST_XR_HZ; xrWaitFrame
// sleeps to the next free slot and predicts display one period later, so a slow application skips
// slots instead of drifting.
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>

#include "runtime.h"

namespace fovrt::xrrt {

XrResult SessionGate(const Session& session) {
    if (session.lost) return XR_ERROR_SESSION_LOST;
    if (session.lossPending) return XR_SESSION_LOSS_PENDING;
    return XR_SUCCESS;
}

void SetSessionState(Session& session, XrSessionState state) {
    session.state = state;
    auto event = XrInit<XrEventDataSessionStateChanged>(XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED);
    event.session = ToHandle<XrSession>(&session);
    event.state = state;
    event.time = Now();
    PushEvent(*session.instance, &event, sizeof event);
    const std::string& dir = session.instance->config.dumpDir;
    if (!dir.empty()) {
        std::error_code ignored;
        std::filesystem::create_directories(dir, ignored);
        std::ofstream(std::filesystem::path(dir) / "states.txt", std::ios::app)
            << SessionStateName(state) << "\n";
    }
}

XrResult SubmitAndWait(Session& session, VkCommandBuffer commandBuffer) {
    auto submit = VkInit<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commandBuffer;
    XRRT_VK(vkQueueSubmit(session.queue, 1, &submit, session.fence));
    XRRT_VK(vkWaitForFences(session.device, 1, &session.fence, VK_TRUE, UINT64_MAX));
    XRRT_VK(vkResetFences(session.device, 1, &session.fence));
    return XR_SUCCESS;
}

void DestroySessionObject(Session* session) {
    while (!session->swapchains.empty()) DestroySwapchainObject(session->swapchains.back());
    for (Space* space : session->spaces) {
        TheRuntime().spaces.erase(space);
        delete space;
    }
    DestroyReadback(*session);
    if (session->fence) vkDestroyFence(session->device, session->fence, nullptr);
    if (session->commandPool) vkDestroyCommandPool(session->device, session->commandPool, nullptr);
    session->instance->session = nullptr;
    TheRuntime().sessions.erase(session);
    delete session;
}

namespace {

XrResult CreateVulkanObjects(Session& s) {
    vkGetDeviceQueue(s.device, s.queueFamily, s.queueIndex, &s.queue);
    if (s.queue == VK_NULL_HANDLE) return XR_ERROR_GRAPHICS_DEVICE_INVALID;
    auto pool = VkInit<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = s.queueFamily;
    XRRT_VK(vkCreateCommandPool(s.device, &pool, nullptr, &s.commandPool));
    auto alloc = VkInit<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    alloc.commandPool = s.commandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    XRRT_VK(vkAllocateCommandBuffers(s.device, &alloc, &s.commandBuffer));
    auto fence = VkInit<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    XRRT_VK(vkCreateFence(s.device, &fence, nullptr, &s.fence));
    return XR_SUCCESS;
}

XrResult XRAPI_CALL CreateSession(XrInstance handle, const XrSessionCreateInfo* info,
                                  XrSession* out) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstance(handle, &instance); XR_FAILED(r)) return r;
    if (!info || !out || info->type != XR_TYPE_SESSION_CREATE_INFO)
        return XR_ERROR_VALIDATION_FAILURE;
    if (XrResult r = CheckSystem(*instance, info->systemId); XR_FAILED(r)) return r;
    auto* binding = FindInChain<XrGraphicsBindingVulkan2KHR>(info->next,
                                                             XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR);
    if (!binding || !instance->Enabled(XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME) ||
        binding->instance == VK_NULL_HANDLE || binding->physicalDevice == VK_NULL_HANDLE ||
        binding->device == VK_NULL_HANDLE)
        return XR_ERROR_GRAPHICS_DEVICE_INVALID;
    if (!instance->graphicsRequirementsQueried) return XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING;
    if (instance->session) return XR_ERROR_LIMIT_REACHED;  // one session per instance
    auto session = std::make_unique<Session>();
    session->instance = instance;
    session->vkInstance = binding->instance;
    session->physicalDevice = binding->physicalDevice;
    session->device = binding->device;
    session->queueFamily = binding->queueFamilyIndex;
    session->queueIndex = binding->queueIndex;
    if (XrResult r = CreateVulkanObjects(*session); XR_FAILED(r)) {
        if (session->fence) vkDestroyFence(session->device, session->fence, nullptr);
        if (session->commandPool)
            vkDestroyCommandPool(session->device, session->commandPool, nullptr);
        return r;
    }
    Session* s = session.release();
    TheRuntime().sessions.insert(s);
    instance->session = s;
    *out = ToHandle<XrSession>(s);
    SetSessionState(*s, XR_SESSION_STATE_IDLE);
    SetSessionState(*s, XR_SESSION_STATE_READY);
    return XR_SUCCESS;
}

XrResult XRAPI_CALL DestroySession(XrSession handle) {
    return DestroyHandle(TheRuntime().sessions, handle, DestroySessionObject);
}

XrDuration Period(const Session& s) { return XrDuration(std::llround(1e9 / s.instance->config.hz)); }

// Steps down to STOPPING the way real runtimes report a user or application exit.
void BeginExit(Session& s) {
    s.exiting = true;
    if (s.state == XR_SESSION_STATE_FOCUSED) SetSessionState(s, XR_SESSION_STATE_VISIBLE);
    if (s.state == XR_SESSION_STATE_VISIBLE) SetSessionState(s, XR_SESSION_STATE_SYNCHRONIZED);
    SetSessionState(s, XR_SESSION_STATE_STOPPING);
}

// FOVRT_TEST_XR_{EXIT,LOSS,INSTANCE_LOSS}_AFTER, checked whenever the ended-frame count changes.
void ScriptedEvents(Session& s) {
    const Config& c = s.instance->config;
    auto reached = [&](int64_t after) { return after >= 0 && s.framesEnded >= uint64_t(after); };
    if (reached(c.exitAfter) && !s.exiting && !s.lossPending) BeginExit(s);
    if (reached(c.lossAfter) && !s.lossPending) {
        s.lossPending = true;
        SetSessionState(s, XR_SESSION_STATE_LOSS_PENDING);
    }
    if (reached(c.instanceLossAfter) && !s.instance->lossEventQueued) {
        s.instance->lossEventQueued = true;
        auto event = XrInit<XrEventDataInstanceLossPending>(XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING);
        event.lossTime = Now() + Period(s);
        PushEvent(*s.instance, &event, sizeof event);
    }
}

XrResult XRAPI_CALL BeginSession(XrSession handle, const XrSessionBeginInfo* info) {
    return OnRunningSession(handle, [&](Session* s) -> XrResult {
        if (!info || info->type != XR_TYPE_SESSION_BEGIN_INFO) return XR_ERROR_VALIDATION_FAILURE;
        if (info->primaryViewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO)
            return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
        if (s->running) return XR_ERROR_SESSION_RUNNING;
        if (s->state != XR_SESSION_STATE_READY) return XR_ERROR_SESSION_NOT_READY;
        s->running = true;
        s->slotOrigin = Now();
        s->lastSlot = 0;
        s->framesWaited = 0;
        s->frameBegun = false;
        ScriptedEvents(*s);
        return XR_SUCCESS;
    });
}

XrResult XRAPI_CALL EndSession(XrSession handle) {
    return OnRunningSession(handle, [&](Session* s) -> XrResult {
        if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
        if (s->state != XR_SESSION_STATE_STOPPING) return XR_ERROR_SESSION_NOT_STOPPING;
        s->running = false;
        s->frameBegun = false;
        s->framesWaited = 0;
        SetSessionState(*s, XR_SESSION_STATE_IDLE);
        if (s->exiting) SetSessionState(*s, XR_SESSION_STATE_EXITING);
        return XR_SUCCESS;
    });
}

XrResult XRAPI_CALL RequestExitSession(XrSession handle) {
    return OnRunningSession(handle, [&](Session* s) -> XrResult {
        if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
        if (!s->exiting) BeginExit(*s);
        return XR_SUCCESS;
    });
}

XrResult XRAPI_CALL WaitFrame(XrSession handle, const XrFrameWaitInfo* info, XrFrameState* state) {
    XrTime wakeAt = 0;
    XrResult gate = XR_SUCCESS;
    {
        auto lock = LockApi();
        Session* s = nullptr;
        if (XrResult r = CheckSession(handle, &s); XR_FAILED(r)) return r;
        gate = SessionGate(*s);
        if (XR_FAILED(gate)) return gate;
        if ((info && info->type != XR_TYPE_FRAME_WAIT_INFO) || !state ||
            state->type != XR_TYPE_FRAME_STATE)
            return XR_ERROR_VALIDATION_FAILURE;
        if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
        XrDuration period = Period(*s);
        int64_t slot = (Now() - s->slotOrigin) / period + 1;
        if (slot <= s->lastSlot) slot = s->lastSlot + 1;
        s->lastSlot = slot;
        wakeAt = s->slotOrigin + slot * period;
        state->predictedDisplayTime = wakeAt + period;
        state->predictedDisplayPeriod = period;
        state->shouldRender = s->state == XR_SESSION_STATE_VISIBLE ||
                              s->state == XR_SESSION_STATE_FOCUSED;
        ++s->framesWaited;
    }
    timespec until{time_t(wakeAt / 1000000000), long(wakeAt % 1000000000)};
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &until, nullptr) == EINTR) {
    }
    return gate;
}

XrResult XRAPI_CALL BeginFrame(XrSession handle, const XrFrameBeginInfo* info) {
    return OnRunningSession(handle, [&](Session* s) -> XrResult {
        if (info && info->type != XR_TYPE_FRAME_BEGIN_INFO) return XR_ERROR_VALIDATION_FAILURE;
        if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
        if (s->framesWaited == 0) return XR_ERROR_CALL_ORDER_INVALID;  // no xrWaitFrame before
        --s->framesWaited;
        if (s->frameBegun) return XR_FRAME_DISCARDED;  // the previous frame never ended
        s->frameBegun = true;
        return XR_SUCCESS;
    });
}

XrResult CheckSubImage(const Session& s, const XrSwapchainSubImage& sub) {
    Swapchain* sc = Find(TheRuntime().swapchains, sub.swapchain);
    if (!sc || sc->session != &s) return XR_ERROR_HANDLE_INVALID;
    if (sc->lastReleased < 0) return XR_ERROR_LAYER_INVALID;  // no image was ever released
    const XrRect2Di& r = sub.imageRect;
    if (r.offset.x < 0 || r.offset.y < 0 || r.extent.width <= 0 || r.extent.height <= 0 ||
        int64_t(r.offset.x) + r.extent.width > int64_t(sc->info.width) ||
        int64_t(r.offset.y) + r.extent.height > int64_t(sc->info.height))
        return XR_ERROR_SWAPCHAIN_RECT_INVALID;
    if (sub.imageArrayIndex >= sc->info.arraySize) return XR_ERROR_VALIDATION_FAILURE;
    return XR_SUCCESS;
}

XrResult CheckLayer(const Session& s, const XrCompositionLayerBaseHeader* layer) {
    if (!layer) return XR_ERROR_LAYER_INVALID;
    Space* space = Find(TheRuntime().spaces, layer->space);
    if (!space || space->session != &s) return XR_ERROR_HANDLE_INVALID;
    if (layer->type == XR_TYPE_COMPOSITION_LAYER_PROJECTION) {
        auto* projection = reinterpret_cast<const XrCompositionLayerProjection*>(layer);
        if (projection->viewCount != kViewCount || !projection->views)
            return XR_ERROR_VALIDATION_FAILURE;
        for (uint32_t i = 0; i < projection->viewCount; ++i) {
            const XrCompositionLayerProjectionView& view = projection->views[i];
            if (view.type != XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW)
                return XR_ERROR_VALIDATION_FAILURE;
            if (!IsUnitQuaternion(view.pose.orientation)) return XR_ERROR_POSE_INVALID;
            if (XrResult r = CheckSubImage(s, view.subImage); XR_FAILED(r)) return r;
        }
        return XR_SUCCESS;
    }
    if (layer->type == XR_TYPE_COMPOSITION_LAYER_QUAD) {  // accepted, not composed
        auto* quad = reinterpret_cast<const XrCompositionLayerQuad*>(layer);
        if (!IsUnitQuaternion(quad->pose.orientation)) return XR_ERROR_POSE_INVALID;
        return CheckSubImage(s, quad->subImage);
    }
    return XR_ERROR_LAYER_INVALID;
}

XrResult XRAPI_CALL EndFrame(XrSession handle, const XrFrameEndInfo* info) {
    return OnRunningSession(handle, [&](Session* s) -> XrResult {
        if (!info || info->type != XR_TYPE_FRAME_END_INFO) return XR_ERROR_VALIDATION_FAILURE;
        if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
        if (!s->frameBegun) return XR_ERROR_CALL_ORDER_INVALID;
        if (info->displayTime <= 0) return XR_ERROR_TIME_INVALID;
        if (info->environmentBlendMode != XR_ENVIRONMENT_BLEND_MODE_OPAQUE)
            return XR_ERROR_ENVIRONMENT_BLEND_MODE_UNSUPPORTED;
        if (info->layerCount > kMaxLayerCount) return XR_ERROR_LAYER_LIMIT_EXCEEDED;
        if (info->layerCount > 0 && !info->layers) return XR_ERROR_VALIDATION_FAILURE;
        for (uint32_t i = 0; i < info->layerCount; ++i)
            if (XrResult r = CheckLayer(*s, info->layers[i]); XR_FAILED(r)) return r;
        s->frameBegun = false;
        if (XrResult r = ReadBackAndDump(*s, *info, s->framesEnded); XR_FAILED(r)) return r;
        ++s->framesEnded;
        if (!s->exiting && !s->lossPending) {
            if (s->state == XR_SESSION_STATE_READY) SetSessionState(*s, XR_SESSION_STATE_SYNCHRONIZED);
            else if (s->state == XR_SESSION_STATE_SYNCHRONIZED)
                SetSessionState(*s, XR_SESSION_STATE_VISIBLE);
            else if (s->state == XR_SESSION_STATE_VISIBLE)
                SetSessionState(*s, XR_SESSION_STATE_FOCUSED);
        }
        ScriptedEvents(*s);
        return XR_SUCCESS;
    });
}

}  // namespace

void AddSessionFunctions(ApiTable& t) {
    t.insert(t.end(), {
        XRRT_CORE(CreateSession), XRRT_CORE(DestroySession), XRRT_CORE(BeginSession),
        XRRT_CORE(EndSession), XRRT_CORE(RequestExitSession), XRRT_CORE(WaitFrame),
        XRRT_CORE(BeginFrame), XRRT_CORE(EndFrame)
    });
}

}  // namespace fovrt::xrrt
