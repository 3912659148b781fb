#include "xr/xr_api.h"

#include <openxr/openxr_reflection.h>

#include "core/error.h"

namespace fovrt {

std::string XrResultName(XrResult result) {
#define FOVRT_XR_RESULT_CASE(name, value) \
    case name: return #name;
    switch (result) {
        XR_LIST_ENUM_XrResult(FOVRT_XR_RESULT_CASE)
        default: return "XrResult " + std::to_string(int(result));
    }
#undef FOVRT_XR_RESULT_CASE
}

std::string XrSessionStateName(XrSessionState state) {
    switch (state) {
        case XR_SESSION_STATE_UNKNOWN: return "UNKNOWN";
        case XR_SESSION_STATE_IDLE: return "IDLE";
        case XR_SESSION_STATE_READY: return "READY";
        case XR_SESSION_STATE_SYNCHRONIZED: return "SYNCHRONIZED";
        case XR_SESSION_STATE_VISIBLE: return "VISIBLE";
        case XR_SESSION_STATE_FOCUSED: return "FOCUSED";
        case XR_SESSION_STATE_STOPPING: return "STOPPING";
        case XR_SESSION_STATE_LOSS_PENDING: return "LOSS_PENDING";
        case XR_SESSION_STATE_EXITING: return "EXITING";
        default: return "state " + std::to_string(int(state));
    }
}

XrResult XrCheck(XrResult result, const char* what) {
    if (XR_FAILED(result)) Fail("{}: {}", what, XrResultName(result));
    return result;
}

}  // namespace fovrt
