#include "xr/xr_eye_gaze.h"

#include <cstring>

#include "core/error.h"
#include "xr/xr_connection.h"

namespace fovrt {
namespace {

XrPath Path(XrInstance instance, const char* path) {
    XrPath p = XR_NULL_PATH;
    XrCheck(xrStringToPath(instance, path, &p), path);
    return p;
}

}  // namespace

XrEyeGaze::XrEyeGaze(const XrConnection& connection, XrSession session) : session_(session) {
    const XrInstance instance = connection.instance();
    auto setInfo = XrInit<XrActionSetCreateInfo>(XR_TYPE_ACTION_SET_CREATE_INFO);
    std::strncpy(setInfo.actionSetName, "fovrt_gaze", XR_MAX_ACTION_SET_NAME_SIZE - 1);
    std::strncpy(setInfo.localizedActionSetName, "fovrt gaze", XR_MAX_LOCALIZED_ACTION_SET_NAME_SIZE - 1);
    XrCheck(xrCreateActionSet(instance, &setInfo, &set_), "xrCreateActionSet");

    auto actionInfo = XrInit<XrActionCreateInfo>(XR_TYPE_ACTION_CREATE_INFO);
    actionInfo.actionType = XR_ACTION_TYPE_POSE_INPUT;
    std::strncpy(actionInfo.actionName, "eye_gaze", XR_MAX_ACTION_NAME_SIZE - 1);
    std::strncpy(actionInfo.localizedActionName, "eye gaze", XR_MAX_LOCALIZED_ACTION_NAME_SIZE - 1);
    XrCheck(xrCreateAction(set_, &actionInfo, &action_), "xrCreateAction");

    XrActionSuggestedBinding binding{action_, Path(instance, "/user/eyes_ext/input/gaze_ext/pose")};
    auto suggested = XrInit<XrInteractionProfileSuggestedBinding>(XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING);
    suggested.interactionProfile = Path(instance, "/interaction_profiles/ext/eye_gaze_interaction");
    suggested.countSuggestedBindings = 1;
    suggested.suggestedBindings = &binding;
    XrCheck(xrSuggestInteractionProfileBindings(instance, &suggested), "xrSuggestInteractionProfileBindings");

    auto attach = XrInit<XrSessionActionSetsAttachInfo>(XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO);
    attach.countActionSets = 1;
    attach.actionSets = &set_;
    XrCheck(xrAttachSessionActionSets(session, &attach), "xrAttachSessionActionSets");

    auto spaceInfo = XrInit<XrActionSpaceCreateInfo>(XR_TYPE_ACTION_SPACE_CREATE_INFO);
    spaceInfo.action = action_;
    spaceInfo.poseInActionSpace.orientation.w = 1.0f;
    XrCheck(xrCreateActionSpace(session, &spaceInfo, &space_), "xrCreateActionSpace");
}

XrEyeGaze::~XrEyeGaze() {
    if (space_ != XR_NULL_HANDLE) xrDestroySpace(space_);
    if (set_ != XR_NULL_HANDLE) xrDestroyActionSet(set_);  // destroys its actions
}

std::optional<XrGazeSample> XrEyeGaze::Locate(XrSpace viewSpace, XrTime time) {
    XrActiveActionSet active{set_, XR_NULL_PATH};
    auto sync = XrInit<XrActionsSyncInfo>(XR_TYPE_ACTIONS_SYNC_INFO);
    sync.countActiveActionSets = 1;
    sync.activeActionSets = &active;
    const XrResult r = xrSyncActions(session_, &sync);
    if (r == XR_SESSION_NOT_FOCUSED) return std::nullopt;  // inputs only flow while FOCUSED
    XrCheck(r, "xrSyncActions");

    auto get = XrInit<XrActionStateGetInfo>(XR_TYPE_ACTION_STATE_GET_INFO);
    get.action = action_;
    auto state = XrInit<XrActionStatePose>(XR_TYPE_ACTION_STATE_POSE);
    XrCheck(xrGetActionStatePose(session_, &get, &state), "xrGetActionStatePose");
    if (!state.isActive) return std::nullopt;

    auto sampleTime = XrInit<XrEyeGazeSampleTimeEXT>(XR_TYPE_EYE_GAZE_SAMPLE_TIME_EXT);
    auto location = XrInit<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
    location.next = &sampleTime;
    XrCheck(xrLocateSpace(space_, viewSpace, time, &location), "xrLocateSpace(eye gaze)");
    if (!(location.locationFlags & XR_SPACE_LOCATION_ORIENTATION_VALID_BIT)) return std::nullopt;
    const XrQuaternionf& q = location.pose.orientation;
    const vec3 direction = glm::normalize(quat(q.w, q.x, q.y, q.z) * vec3(0, 0, -1));
    if (!std::isfinite(direction.x) || !std::isfinite(direction.y) || !std::isfinite(direction.z)) return std::nullopt;
    return XrGazeSample{direction, sampleTime.time != 0 ? sampleTime.time : time};
}

}  // namespace fovrt
