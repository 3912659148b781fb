#include "xr/xr_session.h"

#include <cstdio>

#include "core/error.h"
#include "vk/context.h"
#include "xr/xr_connection.h"

namespace fovrt {

Pose PoseFromXr(const XrPosef& p) {
    Pose pose;
    pose.orientation = quat(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
    pose.position = vec3(p.position.x, p.position.y, p.position.z);
    return pose;
}

XrPosef PoseToXr(const Pose& pose) {
    XrPosef p{};
    p.orientation = {pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w};
    p.position = {pose.position.x, pose.position.y, pose.position.z};
    return p;
}

Fov FovFromXr(const XrFovf& f) {
    Fov fov;
    fov.angleLeft = f.angleLeft;
    fov.angleRight = f.angleRight;
    fov.angleUp = f.angleUp;
    fov.angleDown = f.angleDown;
    return fov;
}

XrFovf FovToXr(const Fov& fov) { return {fov.angleLeft, fov.angleRight, fov.angleUp, fov.angleDown}; }

namespace {

XrSpace CreateReferenceSpace(XrSession session, XrReferenceSpaceType type) {
    auto info = XrInit<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
    info.referenceSpaceType = type;
    info.poseInReferenceSpace.orientation.w = 1.0f;
    XrSpace space = XR_NULL_HANDLE;
    XrCheck(xrCreateReferenceSpace(session, &info, &space), "xrCreateReferenceSpace");
    return space;
}

}  // namespace

XrHeadsetSession::XrHeadsetSession(XrConnection& connection, VulkanContext& context)
    : connection_(connection), context_(context) {
    auto binding = XrInit<XrGraphicsBindingVulkan2KHR>(XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR);
    binding.instance = context.instance();
    binding.physicalDevice = context.physicalDevice();
    binding.device = context.device();
    binding.queueFamilyIndex = context.queueFamily();
    binding.queueIndex = 0;
    auto info = XrInit<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
    info.next = &binding;
    info.systemId = connection.system();
    XrCheck(xrCreateSession(connection.instance(), &info, &session_), "xrCreateSession");
    local_ = CreateReferenceSpace(session_, XR_REFERENCE_SPACE_TYPE_LOCAL);
    view_ = CreateReferenceSpace(session_, XR_REFERENCE_SPACE_TYPE_VIEW);
}

XrHeadsetSession::~XrHeadsetSession() {
    if (view_ != XR_NULL_HANDLE) xrDestroySpace(view_);
    if (local_ != XR_NULL_HANDLE) xrDestroySpace(local_);
    if (session_ != XR_NULL_HANDLE) xrDestroySession(session_);
}

bool XrHeadsetSession::Lost(XrResult result) {
    if (result == XR_ERROR_SESSION_LOST || result == XR_SESSION_LOSS_PENDING) {
        ended_ = XrSessionEnd::SessionLost;
        running_ = false;
        return true;
    }
    if (result == XR_ERROR_INSTANCE_LOST) {
        ended_ = XrSessionEnd::InstanceLost;
        running_ = false;
        return true;
    }
    return false;
}

void XrHeadsetSession::PollEvents() {
    while (ended_ == XrSessionEnd::None) {
        auto event = XrInit<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
        const XrResult r = xrPollEvent(connection_.instance(), &event);
        if (r == XR_EVENT_UNAVAILABLE) return;
        if (Lost(r)) return;
        XrCheck(r, "xrPollEvent");
        switch (event.type) {
            case XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED:
                OnState(reinterpret_cast<const XrEventDataSessionStateChanged&>(event).state);
                break;
            case XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING:
                std::fprintf(stderr, "fovrt xr: the runtime is going away (instance loss pending)\n");
                ended_ = XrSessionEnd::InstanceLost;
                running_ = false;
                return;
            default: break;  // interaction profile changes, reference space changes: nothing to do
        }
    }
}

void XrHeadsetSession::OnState(XrSessionState state) {
    state_ = state;
    statesSeen_.push_back(XrSessionStateName(state));
    std::fprintf(stderr, "fovrt xr: session %s\n", statesSeen_.back().c_str());
    switch (state) {
        case XR_SESSION_STATE_READY: {
            auto begin = XrInit<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
            begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
            const XrResult r = xrBeginSession(session_, &begin);
            if (!Lost(r)) {
                XrCheck(r, "xrBeginSession");
                running_ = true;
            }
            break;
        }
        case XR_SESSION_STATE_STOPPING: {
            running_ = false;
            const XrResult r = xrEndSession(session_);
            if (!Lost(r)) XrCheck(r, "xrEndSession");
            break;
        }
        case XR_SESSION_STATE_EXITING: ended_ = XrSessionEnd::Exited; break;
        case XR_SESSION_STATE_LOSS_PENDING:
            ended_ = XrSessionEnd::SessionLost;
            running_ = false;
            break;
        default: break;
    }
}

void XrHeadsetSession::RequestExit() {
    if (exitRequested_ || ended_ != XrSessionEnd::None) return;
    exitRequested_ = true;
    if (!running_) {
        // Not begun yet (or already stopping): there is no running session to ask to stop.
        if (state_ == XR_SESSION_STATE_IDLE || state_ == XR_SESSION_STATE_UNKNOWN) ended_ = XrSessionEnd::Exited;
        return;
    }
    const XrResult r = xrRequestExitSession(session_);
    if (!Lost(r)) XrCheck(r, "xrRequestExitSession");
}

XrHeadsetSession::FrameTiming XrHeadsetSession::BeginFrame() {
    FrameTiming timing;
    auto waitInfo = XrInit<XrFrameWaitInfo>(XR_TYPE_FRAME_WAIT_INFO);
    auto state = XrInit<XrFrameState>(XR_TYPE_FRAME_STATE);
    XrResult r = xrWaitFrame(session_, &waitInfo, &state);
    if (Lost(r)) return timing;
    XrCheck(r, "xrWaitFrame");
    auto beginInfo = XrInit<XrFrameBeginInfo>(XR_TYPE_FRAME_BEGIN_INFO);
    {
        auto queue = context_.LockQueue();
        r = xrBeginFrame(session_, &beginInfo);
    }
    if (Lost(r)) return timing;
    XrCheck(r, "xrBeginFrame");
    timing.displayTime = state.predictedDisplayTime;
    timing.displayPeriod = state.predictedDisplayPeriod;
    timing.shouldRender = state.shouldRender == XR_TRUE;
    return timing;
}

std::optional<std::array<XrEyeView, 2>> XrHeadsetSession::LocateViews(XrTime time) const {
    auto info = XrInit<XrViewLocateInfo>(XR_TYPE_VIEW_LOCATE_INFO);
    info.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
    info.displayTime = time;
    info.space = local_;
    auto state = XrInit<XrViewState>(XR_TYPE_VIEW_STATE);
    std::array<XrView, 2> views;
    views.fill(XrInit<XrView>(XR_TYPE_VIEW));
    uint32_t count = 0;
    XrCheck(xrLocateViews(session_, &info, &state, 2, &count, views.data()), "xrLocateViews");
    const XrViewStateFlags needed = XR_VIEW_STATE_POSITION_VALID_BIT | XR_VIEW_STATE_ORIENTATION_VALID_BIT;
    if (count != 2 || (state.viewStateFlags & needed) != needed) return std::nullopt;
    std::array<XrEyeView, 2> out;
    for (int eye = 0; eye < 2; ++eye) {
        out[size_t(eye)].pose = PoseFromXr(views[size_t(eye)].pose);
        out[size_t(eye)].fov = FovFromXr(views[size_t(eye)].fov);
    }
    return out;
}

std::optional<Pose> XrHeadsetSession::LocateHead(XrTime time) const {
    auto location = XrInit<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
    XrCheck(xrLocateSpace(view_, local_, time, &location), "xrLocateSpace(VIEW in LOCAL)");
    const XrSpaceLocationFlags needed = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
    if ((location.locationFlags & needed) != needed) return std::nullopt;
    return PoseFromXr(location.pose);
}

void XrHeadsetSession::EndFrame(XrTime displayTime, const std::vector<XrCompositionLayerProjectionView>& views) {
    auto layer = XrInit<XrCompositionLayerProjection>(XR_TYPE_COMPOSITION_LAYER_PROJECTION);
    layer.space = local_;
    layer.viewCount = uint32_t(views.size());
    layer.views = views.data();
    const XrCompositionLayerBaseHeader* layers[] = {reinterpret_cast<const XrCompositionLayerBaseHeader*>(&layer)};
    auto info = XrInit<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
    info.displayTime = displayTime;
    info.environmentBlendMode = connection_.blendMode();
    info.layerCount = views.empty() ? 0 : 1;
    info.layers = views.empty() ? nullptr : layers;
    XrResult r;
    {
        auto queue = context_.LockQueue();
        r = xrEndFrame(session_, &info);
    }
    if (Lost(r)) return;
    XrCheck(r, "xrEndFrame");
    ++framesEnded_;
    if (!views.empty()) ++framesWithLayers_;
}

}  // namespace fovrt
