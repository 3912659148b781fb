// XrHeadsetSession: one OpenXR session on fovrt's Vulkan device (SPEC §11): the session state
// machine, the reference spaces, the frame calls and the view poses.
//
//   IDLE -> READY (xrBeginSession) -> SYNCHRONIZED -> VISIBLE -> FOCUSED
//        -> STOPPING (xrEndSession) -> IDLE -> EXITING (the session is over)
//   LOSS_PENDING, or an instance-loss event: the session is over, lost.
//
// The app polls events every frame (PollEvents), runs frames while Running(), and asks to leave
// with RequestExit (xrRequestExitSession: the runtime then walks the states down to EXITING).
// Vulkan: the runtime may use the context's queue inside xrBeginFrame, xrEndFrame and the
// swapchain calls, so this class and XrEyeSwapchain hold VulkanContext::LockQueue around them.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "xr/xr_api.h"

namespace fovrt {

class VulkanContext;
class XrConnection;

enum class XrSessionEnd {
    None,          // still going
    Exited,        // EXITING after a clean stop
    SessionLost,   // LOSS_PENDING
    InstanceLost,  // XrEventDataInstanceLossPending or XR_ERROR_INSTANCE_LOST
};

// One eye's located view: where it is and what it sees, at the display time asked for.
struct XrEyeView {
    Pose pose;  // world (LOCAL space) from eye
    Fov fov;    // asymmetric, radians
};

class XrHeadsetSession {
public:
    XrHeadsetSession(XrConnection& connection, VulkanContext& context);
    ~XrHeadsetSession();
    XrHeadsetSession(const XrHeadsetSession&) = delete;
    XrHeadsetSession& operator=(const XrHeadsetSession&) = delete;

    XrSession handle() const { return session_; }
    XrSpace localSpace() const { return local_; }
    XrSpace viewSpace() const { return view_; }

    // Handles every queued event: state changes (beginning and ending the session as the states
    // ask), instance loss, interaction profile changes. Logs each state as it arrives.
    void PollEvents();
    // Between xrBeginSession and STOPPING: frames must be run.
    bool Running() const { return running_; }
    XrSessionEnd Ended() const { return ended_; }
    XrSessionState State() const { return state_; }
    // Every state the runtime reported, in order (e.g. "READY", "SYNCHRONIZED", ...).
    const std::vector<std::string>& StatesSeen() const { return statesSeen_; }
    // xrRequestExitSession, once, if the session is running (Ctrl-C, --frames reached).
    void RequestExit();
    bool ExitRequested() const { return exitRequested_; }

    struct FrameTiming {
        XrTime displayTime = 0;
        XrDuration displayPeriod = 0;
        bool shouldRender = false;
    };
    // xrWaitFrame then xrBeginFrame.
    FrameTiming BeginFrame();
    // Both eyes at `time`, in LOCAL space; nullopt unless both position and orientation are valid.
    std::optional<std::array<XrEyeView, 2>> LocateViews(XrTime time) const;
    // The head (VIEW space) in LOCAL space at `time`; nullopt when not valid.
    std::optional<Pose> LocateHead(XrTime time) const;
    // xrEndFrame at `displayTime`: one projection layer (views and swapchains given) or none.
    void EndFrame(XrTime displayTime, const std::vector<XrCompositionLayerProjectionView>& views);
    uint64_t FramesEnded() const { return framesEnded_; }
    uint64_t FramesWithLayers() const { return framesWithLayers_; }

private:
    void OnState(XrSessionState state);
    // XR_ERROR_SESSION_LOST / XR_ERROR_INSTANCE_LOST end the session instead of throwing.
    bool Lost(XrResult result);

    XrConnection& connection_;
    VulkanContext& context_;
    XrSession session_ = XR_NULL_HANDLE;
    XrSpace local_ = XR_NULL_HANDLE;
    XrSpace view_ = XR_NULL_HANDLE;
    XrSessionState state_ = XR_SESSION_STATE_UNKNOWN;
    XrSessionEnd ended_ = XrSessionEnd::None;
    std::vector<std::string> statesSeen_;
    bool running_ = false;
    bool exitRequested_ = false;
    uint64_t framesEnded_ = 0, framesWithLayers_ = 0;
};

// Pose conversions between OpenXR and fovrt (both right-handed, -Z forward, +Y up, metres).
Pose PoseFromXr(const XrPosef& pose);
XrPosef PoseToXr(const Pose& pose);
Fov FovFromXr(const XrFovf& fov);
XrFovf FovToXr(const Fov& fov);

}  // namespace fovrt
