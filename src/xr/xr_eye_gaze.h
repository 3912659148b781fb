// XrEyeGaze: eye tracking through XR_EXT_eye_gaze_interaction (SPEC §11). One action set with one
// pose action bound to /user/eyes_ext/input/gaze_ext/pose of the profile
// /interaction_profiles/ext/eye_gaze_interaction, synced every frame, its action space located in
// VIEW space at the display time. A sample counts only when the action is active and the
// orientation is valid; otherwise the caller falls back to its configured gaze source (real
// runtimes advertise the extension without an eye tracker behind it: the common case).
#pragma once

#include <optional>

#include "core/math.h"
#include "xr/xr_api.h"

namespace fovrt {

class XrConnection;

struct XrGazeSample {
    vec3 directionHead = vec3(0, 0, -1);  // VIEW space = fovrt's head space, unit
    XrTime time = 0;                      // the sample's own time when the runtime gives it
};

class XrEyeGaze {
public:
    // Creates the action set and binding and attaches it to `session` (attach happens once per
    // session, so this is created before the first frame).
    XrEyeGaze(const XrConnection& connection, XrSession session);
    ~XrEyeGaze();
    XrEyeGaze(const XrEyeGaze&) = delete;
    XrEyeGaze& operator=(const XrEyeGaze&) = delete;

    // xrSyncActions, then the gaze at `time` in `viewSpace`; nullopt when the action is inactive or
    // the orientation is not valid.
    std::optional<XrGazeSample> Locate(XrSpace viewSpace, XrTime time);

private:
    XrSession session_;
    XrActionSet set_ = XR_NULL_HANDLE;
    XrAction action_ = XR_NULL_HANDLE;
    XrSpace space_ = XR_NULL_HANDLE;
};

}  // namespace fovrt
