// Actions and XR_EXT_eye_gaze_interaction. The runtime checks two interaction profiles' paths: eye
// gaze (/user/eyes_ext/input/gaze_ext/pose) and khr/simple_controller; other vendors' profiles are
// accepted with any path below /user/hand/*, /user/head or /user/gamepad (ordinary apps suggest
// many), but no controller is ever connected. A pose action is active
// after xrSyncActions only when FOVRT_TEST_XR_GAZE=on, the session is FOCUSED, its set is attached
// and active, and it was suggested for the gaze pose. Boolean/float/vector2f actions are accepted
// and always inactive; haptics are accepted and ignored.
#include <algorithm>
#include <memory>

#include "runtime.h"

namespace fovrt::xrrt {

namespace {

bool IsSimpleControllerPath(const std::string& p) {
    for (const char* hand : {"/user/hand/left", "/user/hand/right"})
        for (const char* input : {"/input/select/click", "/input/menu/click", "/input/grip/pose",
                                  "/input/aim/pose", "/output/haptic"})
            if (p == std::string(hand) + input) return true;
    return false;
}

bool IsTopLevelUserPath(const std::string& p) {
    return p == "/user/hand/left" || p == "/user/hand/right" || p == "/user/head" ||
           p == "/user/gamepad" || p == kEyesUserPath;
}

// /interaction_profiles/<vendor>/<name>
bool IsOtherProfile(const std::string& p) {
    const std::string prefix = "/interaction_profiles/";
    if (p.rfind(prefix, 0) != 0) return false;
    std::string rest = p.substr(prefix.size());
    size_t slash = rest.find('/');
    return slash != std::string::npos && slash > 0 && slash + 1 < rest.size() &&
           rest.find('/', slash + 1) == std::string::npos;
}

// An input or output below a top-level user path, e.g. /user/hand/left/input/trigger/value.
bool IsUnderTopLevelUserPath(const std::string& p) {
    for (const char* top : {"/user/hand/left/", "/user/hand/right/", "/user/head/", "/user/gamepad/"})
        if (p.rfind(top, 0) == 0 && p.size() > std::strlen(top)) return true;
    return false;
}

// Action and action-set names: non-empty, [a-z0-9-_.], shorter than the limit.
bool WellFormedName(const char* name, size_t limit) {
    size_t n = strnlen(name, limit);
    if (n == 0 || n >= limit) return false;
    for (size_t i = 0; i < n; ++i) {
        char c = name[i];
        if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.'))
            return false;
    }
    return true;
}

bool GazeBound(const Instance& instance, const Action* action) {
    auto profile = instance.pathIds.find(kEyeGazeProfile);
    auto pose = instance.pathIds.find(kEyeGazePosePath);
    if (profile == instance.pathIds.end() || pose == instance.pathIds.end()) return false;
    auto bindings = instance.suggested.find(profile->second);
    if (bindings == instance.suggested.end()) return false;
    return std::find(bindings->second.begin(), bindings->second.end(),
                     std::make_pair(const_cast<Action*>(action), pose->second)) !=
           bindings->second.end();
}

XrResult XRAPI_CALL CreateActionSet(XrInstance handle, const XrActionSetCreateInfo* info,
                                    XrActionSet* out) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstance(handle, &instance); XR_FAILED(r)) return r;
    if (!info || !out || info->type != XR_TYPE_ACTION_SET_CREATE_INFO)
        return XR_ERROR_VALIDATION_FAILURE;
    if (!WellFormedName(info->actionSetName, XR_MAX_ACTION_SET_NAME_SIZE))
        return XR_ERROR_PATH_FORMAT_INVALID;
    if (strnlen(info->localizedActionSetName, XR_MAX_LOCALIZED_ACTION_SET_NAME_SIZE) == 0)
        return XR_ERROR_LOCALIZED_NAME_INVALID;
    for (ActionSet* set : instance->actionSets)
        if (set->name == info->actionSetName) return XR_ERROR_NAME_DUPLICATED;
    auto set = std::make_unique<ActionSet>();
    set->instance = instance;
    set->name = info->actionSetName;
    ActionSet* raw = set.release();
    TheRuntime().actionSets.insert(raw);
    instance->actionSets.push_back(raw);
    *out = ToHandle<XrActionSet>(raw);
    return XR_SUCCESS;
}

void DestroyActionObject(Action* action) {
    Instance& instance = *action->set->instance;
    for (auto& [profile, bindings] : instance.suggested)
        bindings.erase(std::remove_if(bindings.begin(), bindings.end(),
                                      [&](const auto& b) { return b.first == action; }),
                       bindings.end());
    if (instance.session) instance.session->activeActions.erase(action);
    for (Space* space : TheRuntime().spaces)  // its action spaces stay, never located again
        if (space->action == action) space->action = nullptr;
    auto& list = action->set->actions;
    list.erase(std::remove(list.begin(), list.end(), action), list.end());
    TheRuntime().actions.erase(action);
    delete action;
}

XrResult XRAPI_CALL DestroyActionSet(XrActionSet handle) {
    return DestroyHandle(TheRuntime().actionSets, handle, DestroyActionSetObject);
}

XrResult XRAPI_CALL CreateAction(XrActionSet handle, const XrActionCreateInfo* info,
                                 XrAction* out) {
    auto lock = LockApi();
    ActionSet* set = Find(TheRuntime().actionSets, handle);
    if (!set) return XR_ERROR_HANDLE_INVALID;
    Instance& instance = *set->instance;
    if (instance.lost) return XR_ERROR_INSTANCE_LOST;
    if (!info || !out || info->type != XR_TYPE_ACTION_CREATE_INFO)
        return XR_ERROR_VALIDATION_FAILURE;
    if (set->attached) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
    if (!WellFormedName(info->actionName, XR_MAX_ACTION_NAME_SIZE))
        return XR_ERROR_PATH_FORMAT_INVALID;
    if (strnlen(info->localizedActionName, XR_MAX_LOCALIZED_ACTION_NAME_SIZE) == 0)
        return XR_ERROR_LOCALIZED_NAME_INVALID;
    for (Action* a : set->actions)
        if (a->name == info->actionName) return XR_ERROR_NAME_DUPLICATED;
    switch (info->actionType) {
        case XR_ACTION_TYPE_BOOLEAN_INPUT:
        case XR_ACTION_TYPE_FLOAT_INPUT:
        case XR_ACTION_TYPE_VECTOR2F_INPUT:
        case XR_ACTION_TYPE_POSE_INPUT:
        case XR_ACTION_TYPE_VIBRATION_OUTPUT:
            break;
        default:
            return XR_ERROR_VALIDATION_FAILURE;
    }
    auto action = std::make_unique<Action>();
    for (uint32_t i = 0; i < info->countSubactionPaths; ++i) {
        XrPath p = info->subactionPaths[i];
        const std::string* s = PathString(instance, p);
        if (!s) return XR_ERROR_PATH_INVALID;
        if (!IsTopLevelUserPath(*s) || std::count(info->subactionPaths,
                                                  info->subactionPaths + i, p) != 0)
            return XR_ERROR_PATH_UNSUPPORTED;
        action->subactionPaths.push_back(p);
    }
    action->set = set;
    action->name = info->actionName;
    action->type = info->actionType;
    Action* raw = action.release();
    TheRuntime().actions.insert(raw);
    set->actions.push_back(raw);
    *out = ToHandle<XrAction>(raw);
    return XR_SUCCESS;
}

XrResult XRAPI_CALL DestroyAction(XrAction handle) {
    return DestroyHandle(TheRuntime().actions, handle, DestroyActionObject);
}

XrResult XRAPI_CALL SuggestInteractionProfileBindings(
    XrInstance handle, const XrInteractionProfileSuggestedBinding* suggested) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstance(handle, &instance); XR_FAILED(r)) return r;
    if (!suggested || suggested->type != XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING ||
        suggested->countSuggestedBindings == 0 || !suggested->suggestedBindings)
        return XR_ERROR_VALIDATION_FAILURE;
    const std::string* profile = PathString(*instance, suggested->interactionProfile);
    if (!profile) return XR_ERROR_PATH_INVALID;
    bool gaze = *profile == kEyeGazeProfile;
    bool simple = *profile == "/interaction_profiles/khr/simple_controller";
    if (gaze && !instance->Enabled(XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME))
        return XR_ERROR_PATH_UNSUPPORTED;
    // Other profiles of the right shape (other vendors' controllers) are accepted and never
    // active, as on a real runtime with none of those devices connected: apps suggest many.
    if (!gaze && !simple && !IsOtherProfile(*profile)) return XR_ERROR_PATH_UNSUPPORTED;
    std::vector<std::pair<Action*, XrPath>> bindings;
    for (uint32_t i = 0; i < suggested->countSuggestedBindings; ++i) {
        const XrActionSuggestedBinding& b = suggested->suggestedBindings[i];
        Action* action = Find(TheRuntime().actions, b.action);
        if (!action || action->set->instance != instance) return XR_ERROR_HANDLE_INVALID;
        if (action->set->attached) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
        const std::string* path = PathString(*instance, b.binding);
        if (!path) return XR_ERROR_PATH_INVALID;
        bool known = gaze     ? *path == kEyeGazePosePath
                     : simple ? IsSimpleControllerPath(*path)
                              : IsUnderTopLevelUserPath(*path);
        if (!known) return XR_ERROR_PATH_UNSUPPORTED;
        bindings.emplace_back(action, b.binding);
    }
    instance->suggested[suggested->interactionProfile] = bindings;  // replaces earlier suggestions
    return XR_SUCCESS;
}

XrResult XRAPI_CALL AttachSessionActionSets(XrSession handle,
                                            const XrSessionActionSetsAttachInfo* info) {
    return OnRunningSession(handle, [&](Session* s) -> XrResult {
        if (!info || info->type != XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO ||
            info->countActionSets == 0 || !info->actionSets)
            return XR_ERROR_VALIDATION_FAILURE;
        if (s->actionSetsAttached) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
        for (uint32_t i = 0; i < info->countActionSets; ++i) {
            ActionSet* set = Find(TheRuntime().actionSets, info->actionSets[i]);
            if (!set || set->instance != s->instance) return XR_ERROR_HANDLE_INVALID;
        }
        for (uint32_t i = 0; i < info->countActionSets; ++i)
            Find(TheRuntime().actionSets, info->actionSets[i])->attached = true;
        s->actionSetsAttached = true;
        // Real runtimes report the (possibly new) current profiles once sets are attached.
        auto event = XrInit<XrEventDataInteractionProfileChanged>(XR_TYPE_EVENT_DATA_INTERACTION_PROFILE_CHANGED);
        event.session = handle;
        PushEvent(*s->instance, &event, sizeof event);
        return XR_SUCCESS;
    });
}

XrResult XRAPI_CALL GetCurrentInteractionProfile(XrSession handle, XrPath topLevelUserPath,
                                                 XrInteractionProfileState* state) {
    return OnRunningSession(handle, [&](Session* s) -> XrResult {
        if (!state || state->type != XR_TYPE_INTERACTION_PROFILE_STATE)
            return XR_ERROR_VALIDATION_FAILURE;
        const std::string* path = PathString(*s->instance, topLevelUserPath);
        if (!path) return XR_ERROR_PATH_INVALID;
        if (!IsTopLevelUserPath(*path)) return XR_ERROR_PATH_UNSUPPORTED;
        if (!s->actionSetsAttached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
        state->interactionProfile = XR_NULL_PATH;
        if (*path == kEyesUserPath && s->instance->config.gaze == GazeMode::On) {
            auto profile = s->instance->pathIds.find(kEyeGazeProfile);
            if (profile != s->instance->pathIds.end() && s->instance->suggested.count(profile->second))
                state->interactionProfile = profile->second;
        }
        return XR_SUCCESS;
    });
}

XrResult XRAPI_CALL SyncActions(XrSession handle, const XrActionsSyncInfo* info) {
    return OnRunningSession(handle, [&](Session* s) -> XrResult {
        if (!info || info->type != XR_TYPE_ACTIONS_SYNC_INFO ||
            (info->countActiveActionSets > 0 && !info->activeActionSets))
            return XR_ERROR_VALIDATION_FAILURE;
        std::vector<ActionSet*> active;
        for (uint32_t i = 0; i < info->countActiveActionSets; ++i) {
            ActionSet* set = Find(TheRuntime().actionSets, info->activeActionSets[i].actionSet);
            if (!set) return XR_ERROR_HANDLE_INVALID;
            if (!set->attached || set->instance != s->instance) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
            if (info->activeActionSets[i].subactionPath != XR_NULL_PATH &&
                !PathString(*s->instance, info->activeActionSets[i].subactionPath))
                return XR_ERROR_PATH_INVALID;
            active.push_back(set);
        }
        s->activeActions.clear();
        if (s->state != XR_SESSION_STATE_FOCUSED) return XR_SESSION_NOT_FOCUSED;  // all inactive
        if (s->instance->config.gaze == GazeMode::On)
            for (ActionSet* set : active)
                for (Action* action : set->actions)
                    if (action->type == XR_ACTION_TYPE_POSE_INPUT && GazeBound(*s->instance, action))
                        s->activeActions.insert(action);
        return XR_SUCCESS;
    });
}

XrResult CheckActionInfo(Session* s, const XrActionStateGetInfo* info, XrActionType type,
                         Action** out) {
    if (!info || info->type != XR_TYPE_ACTION_STATE_GET_INFO) return XR_ERROR_VALIDATION_FAILURE;
    Action* action = Find(TheRuntime().actions, info->action);
    if (!action || action->set->instance != s->instance) return XR_ERROR_HANDLE_INVALID;
    if (action->type != type) return XR_ERROR_ACTION_TYPE_MISMATCH;
    if (!action->set->attached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    if (info->subactionPath != XR_NULL_PATH &&
        std::find(action->subactionPaths.begin(), action->subactionPaths.end(),
                  info->subactionPath) == action->subactionPaths.end())
        return XR_ERROR_PATH_UNSUPPORTED;
    *out = action;
    return XR_SUCCESS;
}

// The shared body of the action-state getters: checks, then fills an inactive or active state.
template <typename State, typename Fill>
XrResult GetActionState(XrSession handle, const XrActionStateGetInfo* info, XrActionType type,
                        XrStructureType stateType, State* state, Fill fill) {
    return OnRunningSession(handle, [&](Session* s) -> XrResult {
        Action* action = nullptr;
        if (XrResult r = CheckActionInfo(s, info, type, &action); XR_FAILED(r)) return r;
        if (!state || state->type != stateType) return XR_ERROR_VALIDATION_FAILURE;
        fill(*state, GazeActionActive(*s, action));
        return XR_SUCCESS;
    });
}

// The fill of a value action's state: this runtime drives none, so each reads inactive, unchanged
// and `zero`.
template <typename State, typename Value>
auto InactiveValue(Value zero) {
    return [zero](State& st, bool) {
        st.currentState = zero;
        st.changedSinceLastSync = XR_FALSE;
        st.lastChangeTime = 0;
        st.isActive = XR_FALSE;
    };
}

XrResult XRAPI_CALL GetActionStateBoolean(XrSession h, const XrActionStateGetInfo* info,
                                          XrActionStateBoolean* state) {
    return GetActionState(h, info, XR_ACTION_TYPE_BOOLEAN_INPUT, XR_TYPE_ACTION_STATE_BOOLEAN, state,
                          InactiveValue<XrActionStateBoolean>(XrBool32(XR_FALSE)));
}

XrResult XRAPI_CALL GetActionStateFloat(XrSession h, const XrActionStateGetInfo* info,
                                        XrActionStateFloat* state) {
    return GetActionState(h, info, XR_ACTION_TYPE_FLOAT_INPUT, XR_TYPE_ACTION_STATE_FLOAT, state,
                          InactiveValue<XrActionStateFloat>(0.0f));
}

XrResult XRAPI_CALL GetActionStateVector2f(XrSession h, const XrActionStateGetInfo* info,
                                           XrActionStateVector2f* state) {
    return GetActionState(h, info, XR_ACTION_TYPE_VECTOR2F_INPUT, XR_TYPE_ACTION_STATE_VECTOR2F, state,
                          InactiveValue<XrActionStateVector2f>(XrVector2f{0.0f, 0.0f}));
}

XrResult XRAPI_CALL GetActionStatePose(XrSession h, const XrActionStateGetInfo* info,
                                       XrActionStatePose* state) {
    return GetActionState(h, info, XR_ACTION_TYPE_POSE_INPUT, XR_TYPE_ACTION_STATE_POSE, state,
                          [](XrActionStatePose& st, bool active) {
                              st.isActive = active ? XR_TRUE : XR_FALSE;
                          });
}

XrResult XRAPI_CALL EnumerateBoundSourcesForAction(
    XrSession handle, const XrBoundSourcesForActionEnumerateInfo* info, uint32_t capacity,
    uint32_t* count, XrPath* sources) {
    auto lock = LockApi();
    Session* s = nullptr;
    if (XrResult r = CheckSession(handle, &s); XR_FAILED(r)) return r;
    if (!info || info->type != XR_TYPE_BOUND_SOURCES_FOR_ACTION_ENUMERATE_INFO)
        return XR_ERROR_VALIDATION_FAILURE;
    Action* action = Find(TheRuntime().actions, info->action);
    if (!action || action->set->instance != s->instance) return XR_ERROR_HANDLE_INVALID;
    if (!action->set->attached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    bool bound = s->instance->config.gaze == GazeMode::On && GazeBound(*s->instance, action);
    XrPath pose = bound ? s->instance->pathIds.at(kEyeGazePosePath) : XR_NULL_PATH;
    return TwoCall(capacity, count, sources, bound ? 1 : 0, [&](XrPath& p, uint32_t) { p = pose; });
}

XrResult XRAPI_CALL GetInputSourceLocalizedName(XrSession handle,
                                                const XrInputSourceLocalizedNameGetInfo* info,
                                                uint32_t capacity, uint32_t* count,
                                                char* buffer) {
    auto lock = LockApi();
    Session* s = nullptr;
    if (XrResult r = CheckSession(handle, &s); XR_FAILED(r)) return r;
    if (!info || info->type != XR_TYPE_INPUT_SOURCE_LOCALIZED_NAME_GET_INFO ||
        info->whichComponents == 0)
        return XR_ERROR_VALIDATION_FAILURE;
    const std::string* path = PathString(*s->instance, info->sourcePath);
    if (!path) return XR_ERROR_PATH_INVALID;
    if (!s->actionSetsAttached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    return TwoCallString(capacity, count, buffer, *path == kEyeGazePosePath ? "Eye gaze" : "");
}

XrResult CheckHaptic(XrSession handle, const XrHapticActionInfo* info) {
    auto lock = LockApi();
    Session* s = nullptr;
    if (XrResult r = CheckSession(handle, &s); XR_FAILED(r)) return r;
    if (!info || info->type != XR_TYPE_HAPTIC_ACTION_INFO) return XR_ERROR_VALIDATION_FAILURE;
    Action* action = Find(TheRuntime().actions, info->action);
    if (!action || action->set->instance != s->instance) return XR_ERROR_HANDLE_INVALID;
    if (action->type != XR_ACTION_TYPE_VIBRATION_OUTPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
    if (!action->set->attached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    return SessionGate(*s);
}

XrResult XRAPI_CALL ApplyHapticFeedback(XrSession handle, const XrHapticActionInfo* info,
                                        const XrHapticBaseHeader* haptic) {
    if (!haptic) return XR_ERROR_VALIDATION_FAILURE;
    return CheckHaptic(handle, info);
}

XrResult XRAPI_CALL StopHapticFeedback(XrSession handle, const XrHapticActionInfo* info) {
    return CheckHaptic(handle, info);
}

}  // namespace

bool GazeActionActive(const Session& session, const Action* action) {
    return session.activeActions.count(const_cast<Action*>(action)) != 0;
}

void DestroyActionSetObject(ActionSet* set) {
    while (!set->actions.empty()) DestroyActionObject(set->actions.back());
    auto& list = set->instance->actionSets;
    list.erase(std::remove(list.begin(), list.end(), set), list.end());
    TheRuntime().actionSets.erase(set);
    delete set;
}

void AddActionFunctions(ApiTable& t) {
    t.insert(t.end(), {
        XRRT_CORE(CreateActionSet), XRRT_CORE(DestroyActionSet), XRRT_CORE(CreateAction),
        XRRT_CORE(DestroyAction), XRRT_CORE(SuggestInteractionProfileBindings),
        XRRT_CORE(AttachSessionActionSets), XRRT_CORE(GetCurrentInteractionProfile),
        XRRT_CORE(SyncActions), XRRT_CORE(GetActionStateBoolean), XRRT_CORE(GetActionStateFloat),
        XRRT_CORE(GetActionStateVector2f), XRRT_CORE(GetActionStatePose),
        XRRT_CORE(EnumerateBoundSourcesForAction), XRRT_CORE(GetInputSourceLocalizedName),
        XRRT_CORE(ApplyHapticFeedback), XRRT_CORE(StopHapticFeedback)
    });
}

}  // namespace fovrt::xrrt
