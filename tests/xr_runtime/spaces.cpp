// Spaces and views. Every space is placed in STAGE space at the asked time and located relative to
// another as inverse(base) * space. LOCAL and STAGE coincide (floor-level origin, head at about
// 1.6 m); VIEW follows the scripted head (motion.h); the eye-gaze action space is VIEW rotated by
// the gaze orientation, and is valid only while the gaze action is active.
#include <algorithm>
#include <memory>

#include "runtime.h"

namespace fovrt::xrrt {

glm::vec3 GazeDirection(const Config& config, XrTime time) {
    return config.gazeFixed ? GazeFromTangent(config.gazeTx, config.gazeTy) : ScriptedGaze(time);
}

Pose SpaceInStage(const Space& space, XrTime time, bool* valid, XrTime* gazeSampleTime) {
    *valid = true;
    if (!space.isAction) {
        if (space.referenceType == XR_REFERENCE_SPACE_TYPE_VIEW)
            return Compose(HeadPose(time), space.offset);
        return space.offset;
    }
    if (!space.action || !GazeActionActive(*space.session, space.action)) {
        *valid = false;
        return {};
    }
    // An eye tracker reports its latest sample, never a prediction: the sample time is the asked
    // time or now, whichever is earlier, and the gaze is the script's value at that time.
    XrTime sample = std::min(time, Now());
    if (gazeSampleTime) *gazeSampleTime = sample;
    Pose gaze;
    gaze.orientation = GazeOrientation(GazeDirection(space.session->instance->config, sample));
    return Compose(Compose(HeadPose(time), gaze), space.offset);
}

namespace {

bool SupportedReferenceSpace(XrReferenceSpaceType type) {
    return type == XR_REFERENCE_SPACE_TYPE_VIEW || type == XR_REFERENCE_SPACE_TYPE_LOCAL ||
           type == XR_REFERENCE_SPACE_TYPE_STAGE;
}

XrResult AddSpace(Session& s, std::unique_ptr<Space> space, XrSpace* out) {
    Space* raw = space.release();
    TheRuntime().spaces.insert(raw);
    s.spaces.push_back(raw);
    *out = ToHandle<XrSpace>(raw);
    return XR_SUCCESS;
}

XrResult XRAPI_CALL EnumerateReferenceSpaces(XrSession handle, uint32_t capacity, uint32_t* count,
                                             XrReferenceSpaceType* spaces) {
    auto lock = LockApi();
    Session* s = nullptr;
    if (XrResult r = CheckSession(handle, &s); XR_FAILED(r)) return r;
    constexpr XrReferenceSpaceType kTypes[] = {XR_REFERENCE_SPACE_TYPE_VIEW,
                                               XR_REFERENCE_SPACE_TYPE_LOCAL,
                                               XR_REFERENCE_SPACE_TYPE_STAGE};
    return TwoCall(capacity, count, spaces, 3,
                   [&](XrReferenceSpaceType& t, uint32_t i) { t = kTypes[i]; });
}

XrResult XRAPI_CALL CreateReferenceSpace(XrSession handle, const XrReferenceSpaceCreateInfo* info,
                                         XrSpace* out) {
    auto lock = LockApi();
    Session* s = nullptr;
    if (XrResult r = CheckSession(handle, &s); XR_FAILED(r)) return r;
    if (!info || !out || info->type != XR_TYPE_REFERENCE_SPACE_CREATE_INFO)
        return XR_ERROR_VALIDATION_FAILURE;
    if (!SupportedReferenceSpace(info->referenceSpaceType))
        return XR_ERROR_REFERENCE_SPACE_UNSUPPORTED;
    if (!IsUnitQuaternion(info->poseInReferenceSpace.orientation)) return XR_ERROR_POSE_INVALID;
    auto space = std::make_unique<Space>();
    space->session = s;
    space->referenceType = info->referenceSpaceType;
    space->offset = FromXr(info->poseInReferenceSpace);
    return AddSpace(*s, std::move(space), out);
}

XrResult XRAPI_CALL GetReferenceSpaceBoundsRect(XrSession handle, XrReferenceSpaceType type,
                                                XrExtent2Df* bounds) {
    auto lock = LockApi();
    Session* s = nullptr;
    if (XrResult r = CheckSession(handle, &s); XR_FAILED(r)) return r;
    if (!bounds) return XR_ERROR_VALIDATION_FAILURE;
    if (!SupportedReferenceSpace(type)) return XR_ERROR_REFERENCE_SPACE_UNSUPPORTED;
    if (type == XR_REFERENCE_SPACE_TYPE_STAGE) {
        *bounds = {2.0f, 2.0f};  // a 2 m x 2 m play area
        return XR_SUCCESS;
    }
    *bounds = {0.0f, 0.0f};
    return XR_SPACE_BOUNDS_UNAVAILABLE;
}

XrResult XRAPI_CALL CreateActionSpace(XrSession handle, const XrActionSpaceCreateInfo* info,
                                      XrSpace* out) {
    auto lock = LockApi();
    Session* s = nullptr;
    if (XrResult r = CheckSession(handle, &s); XR_FAILED(r)) return r;
    if (!info || !out || info->type != XR_TYPE_ACTION_SPACE_CREATE_INFO)
        return XR_ERROR_VALIDATION_FAILURE;
    Action* action = Find(TheRuntime().actions, info->action);
    if (!action || action->set->instance != s->instance) return XR_ERROR_HANDLE_INVALID;
    if (action->type != XR_ACTION_TYPE_POSE_INPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
    if (info->subactionPath != XR_NULL_PATH) {
        if (!PathString(*s->instance, info->subactionPath)) return XR_ERROR_PATH_INVALID;
        const auto& paths = action->subactionPaths;
        if (std::find(paths.begin(), paths.end(), info->subactionPath) == paths.end())
            return XR_ERROR_PATH_UNSUPPORTED;
    }
    if (!IsUnitQuaternion(info->poseInActionSpace.orientation)) return XR_ERROR_POSE_INVALID;
    auto space = std::make_unique<Space>();
    space->session = s;
    space->isAction = true;
    space->action = action;
    space->offset = FromXr(info->poseInActionSpace);
    return AddSpace(*s, std::move(space), out);
}

XrResult XRAPI_CALL DestroySpace(XrSpace handle) {
    return DestroyHandle(TheRuntime().spaces, handle, [](Space* space) {
        auto& list = space->session->spaces;
        list.erase(std::remove(list.begin(), list.end(), space), list.end());
        TheRuntime().spaces.erase(space);
        delete space;
    });
}

constexpr XrSpaceLocationFlags kAllLocationFlags =
    XR_SPACE_LOCATION_ORIENTATION_VALID_BIT | XR_SPACE_LOCATION_POSITION_VALID_BIT |
    XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT | XR_SPACE_LOCATION_POSITION_TRACKED_BIT;

XrResult XRAPI_CALL LocateSpace(XrSpace spaceHandle, XrSpace baseHandle, XrTime time,
                                XrSpaceLocation* location) {
    auto lock = LockApi();
    Space* space = Find(TheRuntime().spaces, spaceHandle);
    Space* base = Find(TheRuntime().spaces, baseHandle);
    if (!space || !base) return XR_ERROR_HANDLE_INVALID;
    if (space->session->instance->lost) return XR_ERROR_INSTANCE_LOST;
    XrResult gate = SessionGate(*space->session);
    if (XR_FAILED(gate)) return gate;
    if (space->session != base->session || !location || location->type != XR_TYPE_SPACE_LOCATION)
        return XR_ERROR_VALIDATION_FAILURE;
    if (time <= 0) return XR_ERROR_TIME_INVALID;
    bool spaceValid = false, baseValid = false;
    XrTime sampleTime = 0;
    Pose a = SpaceInStage(*space, time, &spaceValid, &sampleTime);
    Pose b = SpaceInStage(*base, time, &baseValid, &sampleTime);
    bool valid = spaceValid && baseValid;
    location->locationFlags = valid ? kAllLocationFlags : 0;
    location->pose = ToXr(valid ? Compose(Inverse(b), a) : Pose{});
    if (auto* velocity = FindInChain<XrSpaceVelocity>(location->next, XR_TYPE_SPACE_VELOCITY))
        velocity->velocityFlags = 0;  // the simulated HMD reports no velocities
    if (auto* sample = FindInChain<XrEyeGazeSampleTimeEXT>(location->next,
                                                            XR_TYPE_EYE_GAZE_SAMPLE_TIME_EXT))
        sample->time = valid ? sampleTime : 0;
    return gate;
}

XrResult XRAPI_CALL LocateViews(XrSession handle, const XrViewLocateInfo* info, XrViewState* state,
                                uint32_t capacity, uint32_t* count, XrView* views) {
    return OnRunningSession(handle, [&](Session* s) -> XrResult {
        if (!info || info->type != XR_TYPE_VIEW_LOCATE_INFO || !state ||
            state->type != XR_TYPE_VIEW_STATE)
            return XR_ERROR_VALIDATION_FAILURE;
        if (info->viewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO)
            return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
        if (info->displayTime <= 0) return XR_ERROR_TIME_INVALID;
        Space* space = Find(TheRuntime().spaces, info->space);
        if (!space || space->session != s) return XR_ERROR_HANDLE_INVALID;
        if (views)
            for (uint32_t i = 0; i < std::min(capacity, kViewCount); ++i)
                if (views[i].type != XR_TYPE_VIEW) return XR_ERROR_VALIDATION_FAILURE;
        bool baseValid = false;
        Pose base = SpaceInStage(*space, info->displayTime, &baseValid, nullptr);
        Pose head = HeadPose(info->displayTime);
        state->viewStateFlags = baseValid ? kAllLocationFlags : 0;
        return TwoCall(capacity, count, views, kViewCount, [&](XrView& view, uint32_t eye) {
            view.pose = ToXr(baseValid ? Compose(Inverse(base), Compose(head, EyeFromHead(int(eye))))
                                       : Pose{});
            Fov fov = EyeFov(int(eye));
            view.fov = {fov.angleLeft, fov.angleRight, fov.angleUp, fov.angleDown};
        });
    });
}

}  // namespace

void AddSpaceFunctions(ApiTable& t) {
    t.insert(t.end(), {
        XRRT_CORE(EnumerateReferenceSpaces), XRRT_CORE(CreateReferenceSpace),
        XRRT_CORE(GetReferenceSpaceBoundsRect), XRRT_CORE(CreateActionSpace), XRRT_CORE(DestroySpace),
        XRRT_CORE(LocateSpace), XRRT_CORE(LocateViews)
    });
}

}  // namespace fovrt::xrrt
