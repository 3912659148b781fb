// Instance and system: the FOVRT_TEST_XR_* configuration, extensions, the event queue, paths,
// enum strings, time conversion, and the simulated HMD's system and view configuration.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>

#include <openxr/openxr_reflection.h>

#include "runtime.h"

namespace fovrt::xrrt {

namespace {

bool ParseCount(const char* text, int64_t* value) {
    char* end = nullptr;
    long long v = std::strtoll(text, &end, 10);
    if (end == text || *end != '\0' || v < 0) return false;
    *value = v;
    return true;
}

bool ParseFlag(const char* text, bool* value) {
    std::string s(text);
    if (s == "1" || s == "on" || s == "true") *value = true;
    else if (s == "0" || s == "off" || s == "false" || s.empty()) *value = false;
    else return false;
    return true;
}

}  // namespace

bool Config::FromEnvironment(Config* config, std::string* error) {
    Config c;
    auto bad = [error](const char* name, const char* value, const char* expected) {
        *error = std::string(name) + "='" + value + "': expected " + expected;
        return false;
    };
    if (const char* v = std::getenv("FOVRT_TEST_XR_SIZE")) {
        unsigned w = 0, h = 0;
        char tail = 0;
        if (std::sscanf(v, "%ux%u%c", &w, &h, &tail) != 2 || w == 0 || h == 0 ||
            w > kMaxImageSize || h > kMaxImageSize)
            return bad("FOVRT_TEST_XR_SIZE", v, "WxH, each 1..2048");
        c.width = w;
        c.height = h;
    }
    if (const char* v = std::getenv("FOVRT_TEST_XR_HZ")) {
        char* end = nullptr;
        double hz = std::strtod(v, &end);
        if (end == v || *end != '\0' || !(hz >= 1.0 && hz <= 1000.0))
            return bad("FOVRT_TEST_XR_HZ", v, "a rate in Hz, 1..1000");
        c.hz = hz;
    }
    if (const char* v = std::getenv("FOVRT_TEST_XR_GAZE")) {
        std::string s(v);
        if (s == "on") c.gaze = GazeMode::On;
        else if (s == "off" || s.empty()) c.gaze = GazeMode::Off;
        else if (s == "unsupported") c.gaze = GazeMode::Unsupported;
        else return bad("FOVRT_TEST_XR_GAZE", v, "on, off or unsupported");
    }
    if (const char* v = std::getenv("FOVRT_TEST_XR_GAZE_FIXED")) {
        float tx = 0, ty = 0;
        char tail = 0;
        if (std::sscanf(v, "%f,%f%c", &tx, &ty, &tail) != 2)
            return bad("FOVRT_TEST_XR_GAZE_FIXED", v, "tx,ty (tangent-space gaze, e.g. 0.2,-0.1)");
        c.gazeFixed = true;
        c.gazeTx = tx;
        c.gazeTy = ty;
    }
    struct FlagVar {
        const char* name;
        bool* value;
    };
    for (FlagVar f : {FlagVar{"FOVRT_TEST_XR_NO_ENABLE2", &c.noEnable2},
                      FlagVar{"FOVRT_TEST_XR_NO_HMD", &c.noHmd},
                      FlagVar{"FOVRT_TEST_XR_FORM_FACTOR_UNSUPPORTED", &c.formFactorUnsupported}})
        if (const char* v = std::getenv(f.name))
            if (!ParseFlag(v, f.value)) return bad(f.name, v, "1 or 0");
    struct CountVar {
        const char* name;
        int64_t* value;
    };
    for (CountVar f : {CountVar{"FOVRT_TEST_XR_EXIT_AFTER", &c.exitAfter},
                       CountVar{"FOVRT_TEST_XR_LOSS_AFTER", &c.lossAfter},
                       CountVar{"FOVRT_TEST_XR_INSTANCE_LOSS_AFTER", &c.instanceLossAfter}})
        if (const char* v = std::getenv(f.name))
            if (!ParseCount(v, f.value)) return bad(f.name, v, "a frame count >= 0");
    if (const char* v = std::getenv("FOVRT_TEST_XR_DUMP")) c.dumpDir = v;
    *config = c;
    return true;
}

XrPath InternPath(Instance& instance, const std::string& path) {
    auto it = instance.pathIds.find(path);
    if (it != instance.pathIds.end()) return it->second;
    instance.paths.push_back(path);
    XrPath id = instance.paths.size();
    instance.pathIds[path] = id;
    return id;
}

const std::string* PathString(const Instance& instance, XrPath path) {
    if (path == XR_NULL_PATH || path > instance.paths.size()) return nullptr;
    return &instance.paths[path - 1];
}

void PushEvent(Instance& instance, const void* event, size_t size) {
    Instance::Event e{};
    std::memcpy(&e.data, event, size);
    e.size = size;
    instance.events.push_back(e);
}

const char* SessionStateName(XrSessionState state) {
    switch (state) {
#define FOVRT_XR_STATE_CASE(name, value) \
    case name:                           \
        return #name;
        XR_LIST_ENUM_XrSessionState(FOVRT_XR_STATE_CASE)
#undef FOVRT_XR_STATE_CASE
        default:
            return "XR_SESSION_STATE_UNKNOWN";
    }
}

namespace {

std::vector<std::string> AvailableExtensions(const Config& config) {
    std::vector<std::string> list;
    if (!config.noEnable2) list.push_back(XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME);
    list.push_back(XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME);
    list.push_back(XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME);
    return list;
}

uint32_t ExtensionVersion(const std::string& name) {
    if (name == XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME) return XR_KHR_vulkan_enable2_SPEC_VERSION;
    if (name == XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME)
        return XR_EXT_eye_gaze_interaction_SPEC_VERSION;
    return XR_KHR_convert_timespec_time_SPEC_VERSION;
}

XrResult XRAPI_CALL EnumerateInstanceExtensionProperties(const char* layerName,
                                                         uint32_t capacity, uint32_t* count,
                                                         XrExtensionProperties* properties) {
    if (layerName && layerName[0]) return XR_ERROR_API_LAYER_NOT_PRESENT;
    // The advertised list depends on the environment (FOVRT_TEST_XR_NO_ENABLE2), read now.
    Config config;
    std::string error;
    if (!Config::FromEnvironment(&config, &error)) config = Config();
    std::vector<std::string> list = AvailableExtensions(config);
    if (properties)
        for (uint32_t i = 0; i < capacity; ++i)
            if (properties[i].type != XR_TYPE_EXTENSION_PROPERTIES)
                return XR_ERROR_VALIDATION_FAILURE;
    return TwoCall(capacity, count, properties, uint32_t(list.size()),
                   [&](XrExtensionProperties& p, uint32_t i) {
                       std::snprintf(p.extensionName, sizeof p.extensionName, "%s",
                                     list[i].c_str());
                       p.extensionVersion = ExtensionVersion(list[i]);
                   });
}

XrResult XRAPI_CALL EnumerateApiLayerProperties(uint32_t, uint32_t* count, XrApiLayerProperties*) {
    if (!count) return XR_ERROR_VALIDATION_FAILURE;
    *count = 0;  // the loader lists layers; a runtime has none
    return XR_SUCCESS;
}

XrResult XRAPI_CALL CreateInstance(const XrInstanceCreateInfo* info, XrInstance* out) {
    if (!info || !out || info->type != XR_TYPE_INSTANCE_CREATE_INFO)
        return XR_ERROR_VALIDATION_FAILURE;
    if (XR_VERSION_MAJOR(info->applicationInfo.apiVersion) != 1)
        return XR_ERROR_API_VERSION_UNSUPPORTED;
    if (info->applicationInfo.applicationName[0] == '\0') return XR_ERROR_NAME_INVALID;
    Config config;
    std::string error;
    if (!Config::FromEnvironment(&config, &error)) {
        Log(error);
        return XR_ERROR_INITIALIZATION_FAILED;
    }
    std::vector<std::string> available = AvailableExtensions(config);
    auto instance = std::make_unique<Instance>();
    for (uint32_t i = 0; i < info->enabledExtensionCount; ++i) {
        std::string name = info->enabledExtensionNames[i];
        if (std::find(available.begin(), available.end(), name) == available.end())
            return XR_ERROR_EXTENSION_NOT_PRESENT;
        instance->extensions.insert(name);
    }
    instance->config = config;
    auto lock = LockApi();
    Instance* raw = instance.release();
    TheRuntime().instances.insert(raw);
    *out = ToHandle<XrInstance>(raw);
    return XR_SUCCESS;
}

XrResult XRAPI_CALL DestroyInstance(XrInstance handle) {
    return DestroyHandle(TheRuntime().instances, handle, [](Instance* instance) {
        if (instance->session) DestroySessionObject(instance->session);
        while (!instance->actionSets.empty()) DestroyActionSetObject(instance->actionSets.back());
        TheRuntime().instances.erase(instance);
        delete instance;
    });
}

XrResult XRAPI_CALL GetInstanceProperties(XrInstance handle, XrInstanceProperties* properties) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstance(handle, &instance); XR_FAILED(r)) return r;
    if (!properties || properties->type != XR_TYPE_INSTANCE_PROPERTIES)
        return XR_ERROR_VALIDATION_FAILURE;
    properties->runtimeVersion = XR_MAKE_VERSION(0, 1, 0);
    std::snprintf(properties->runtimeName, sizeof properties->runtimeName, "fovrt test runtime");
    return XR_SUCCESS;
}

XrResult XRAPI_CALL PollEvent(XrInstance handle, XrEventDataBuffer* buffer) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstance(handle, &instance); XR_FAILED(r)) return r;
    if (!buffer) return XR_ERROR_VALIDATION_FAILURE;
    if (instance->events.empty()) return XR_EVENT_UNAVAILABLE;
    Instance::Event e = instance->events.front();
    instance->events.pop_front();
    std::memcpy(buffer, &e.data, e.size);
    // Once the application has seen the loss warning, the instance is gone.
    if (e.data.type == XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING) instance->lost = true;
    // Likewise for a session once it has been told it is being lost.
    if (e.data.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) {
        auto& changed = reinterpret_cast<const XrEventDataSessionStateChanged&>(e.data);
        if (Session* s = Find(TheRuntime().sessions, changed.session);
            s && changed.state == XR_SESSION_STATE_LOSS_PENDING)
            s->lost = true;
    }
    return XR_SUCCESS;
}

#define XRRT_ENUM_NAME_CASE(n, v) \
    case n:                       \
        return #n;
const char* ResultName(XrResult value) {
    switch (value) {
        XR_LIST_ENUM_XrResult(XRRT_ENUM_NAME_CASE) default : return nullptr;
    }
}
const char* StructureTypeName(XrStructureType value) {
    switch (value) {
        XR_LIST_ENUM_XrStructureType(XRRT_ENUM_NAME_CASE) default : return nullptr;
    }
}
#undef XRRT_ENUM_NAME_CASE

// xrResultToString / xrStructureTypeToString: the enum's name, or `fallback` for an unknown value.
XrResult WriteEnumName(XrInstance handle, const char* name, const std::string& fallback, char* buffer,
                       size_t size) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstance(handle, &instance); XR_FAILED(r)) return r;
    std::snprintf(buffer, size, "%s", name ? name : fallback.c_str());
    return XR_SUCCESS;
}

XrResult XRAPI_CALL ResultToString(XrInstance handle, XrResult value, char buffer[]) {
    const std::string fallback = std::string("XR_UNKNOWN_") + (XR_SUCCEEDED(value) ? "SUCCESS" : "FAILURE") +
                                 "_" + std::to_string(int(value));
    return WriteEnumName(handle, ResultName(value), fallback, buffer, XR_MAX_RESULT_STRING_SIZE);
}

XrResult XRAPI_CALL StructureTypeToString(XrInstance handle, XrStructureType value, char buffer[]) {
    return WriteEnumName(handle, StructureTypeName(value), "XR_UNKNOWN_STRUCTURE_TYPE_" + std::to_string(int(value)),
                         buffer, XR_MAX_STRUCTURE_NAME_SIZE);
}

// OpenXR path syntax: "/seg/seg", segments of [a-z0-9-_.] that are not all dots.
bool WellFormedPath(const char* text) {
    std::string s(text);
    if (s.size() < 2 || s.size() >= XR_MAX_PATH_LENGTH || s[0] != '/' || s.back() == '/')
        return false;
    std::string segment;
    for (size_t i = 1; i <= s.size(); ++i) {
        char c = i < s.size() ? s[i] : '/';
        if (c == '/') {
            if (segment.empty() || segment.find_first_not_of('.') == std::string::npos)
                return false;
            segment.clear();
        } else if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_' ||
                   c == '.') {
            segment += c;
        } else {
            return false;
        }
    }
    return true;
}

XrResult XRAPI_CALL StringToPath(XrInstance handle, const char* text, XrPath* path) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstance(handle, &instance); XR_FAILED(r)) return r;
    if (!text || !path) return XR_ERROR_VALIDATION_FAILURE;
    if (!WellFormedPath(text)) return XR_ERROR_PATH_FORMAT_INVALID;
    *path = InternPath(*instance, text);
    return XR_SUCCESS;
}

XrResult XRAPI_CALL PathToString(XrInstance handle, XrPath path, uint32_t capacity,
                                 uint32_t* count, char* buffer) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstance(handle, &instance); XR_FAILED(r)) return r;
    const std::string* s = PathString(*instance, path);
    if (!s) return XR_ERROR_PATH_INVALID;
    return TwoCallString(capacity, count, buffer, *s);
}

XrResult XRAPI_CALL GetSystem(XrInstance handle, const XrSystemGetInfo* info, XrSystemId* id) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstance(handle, &instance); XR_FAILED(r)) return r;
    if (!info || !id || info->type != XR_TYPE_SYSTEM_GET_INFO) return XR_ERROR_VALIDATION_FAILURE;
    if (info->formFactor != XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY &&
        info->formFactor != XR_FORM_FACTOR_HANDHELD_DISPLAY)
        return XR_ERROR_FORM_FACTOR_UNSUPPORTED;
    if (instance->config.formFactorUnsupported ||
        info->formFactor != XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY)
        return XR_ERROR_FORM_FACTOR_UNSUPPORTED;
    if (instance->config.noHmd) return XR_ERROR_FORM_FACTOR_UNAVAILABLE;
    instance->systemQueried = true;
    *id = kSystemId;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL GetSystemProperties(XrInstance handle, XrSystemId id,
                                        XrSystemProperties* properties) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstanceSystem(handle, id, &instance); XR_FAILED(r)) return r;
    if (!properties || properties->type != XR_TYPE_SYSTEM_PROPERTIES)
        return XR_ERROR_VALIDATION_FAILURE;
    properties->systemId = id;
    properties->vendorId = 0xF0F7;
    std::snprintf(properties->systemName, sizeof properties->systemName, "fovrt test HMD");
    properties->graphicsProperties.maxSwapchainImageWidth = kMaxImageSize;
    properties->graphicsProperties.maxSwapchainImageHeight = kMaxImageSize;
    properties->graphicsProperties.maxLayerCount = kMaxLayerCount;
    properties->trackingProperties.orientationTracking = XR_TRUE;
    properties->trackingProperties.positionTracking = XR_TRUE;
    if (auto* gaze = FindInChain<XrSystemEyeGazeInteractionPropertiesEXT>(
            properties->next, XR_TYPE_SYSTEM_EYE_GAZE_INTERACTION_PROPERTIES_EXT))
        gaze->supportsEyeGazeInteraction =
            instance->config.gaze == GazeMode::Unsupported ? XR_FALSE : XR_TRUE;
    return XR_SUCCESS;
}

// The view-configuration calls: a known instance and system, and the one configuration there is.
XrResult CheckStereoViewConfiguration(XrInstance handle, XrSystemId id, XrViewConfigurationType type,
                                      Instance** out) {
    if (XrResult r = CheckInstanceSystem(handle, id, out); XR_FAILED(r)) return r;
    return type == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO ? XR_SUCCESS
                                                             : XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
}

XrResult XRAPI_CALL EnumerateViewConfigurations(XrInstance handle, XrSystemId id,
                                                uint32_t capacity, uint32_t* count,
                                                XrViewConfigurationType* types) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstanceSystem(handle, id, &instance); XR_FAILED(r)) return r;
    return TwoCall(capacity, count, types, 1, [](XrViewConfigurationType& t, uint32_t) {
        t = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
    });
}

XrResult XRAPI_CALL GetViewConfigurationProperties(XrInstance handle, XrSystemId id,
                                                   XrViewConfigurationType type,
                                                   XrViewConfigurationProperties* properties) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckStereoViewConfiguration(handle, id, type, &instance); XR_FAILED(r)) return r;
    if (!properties || properties->type != XR_TYPE_VIEW_CONFIGURATION_PROPERTIES)
        return XR_ERROR_VALIDATION_FAILURE;
    properties->viewConfigurationType = type;
    properties->fovMutable = XR_FALSE;  // the app renders the FOVs xrLocateViews gives
    return XR_SUCCESS;
}

XrResult XRAPI_CALL EnumerateViewConfigurationViews(XrInstance handle, XrSystemId id,
                                                    XrViewConfigurationType type,
                                                    uint32_t capacity, uint32_t* count,
                                                    XrViewConfigurationView* views) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckStereoViewConfiguration(handle, id, type, &instance); XR_FAILED(r)) return r;
    const Config& c = instance->config;
    return TwoCall(capacity, count, views, kViewCount, [&](XrViewConfigurationView& v, uint32_t) {
        v.recommendedImageRectWidth = c.width;
        v.recommendedImageRectHeight = c.height;
        v.maxImageRectWidth = kMaxImageSize;
        v.maxImageRectHeight = kMaxImageSize;
        v.recommendedSwapchainSampleCount = 1;
        v.maxSwapchainSampleCount = 1;
    });
}

XrResult XRAPI_CALL EnumerateEnvironmentBlendModes(XrInstance handle, XrSystemId id,
                                                   XrViewConfigurationType type,
                                                   uint32_t capacity, uint32_t* count,
                                                   XrEnvironmentBlendMode* modes) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckStereoViewConfiguration(handle, id, type, &instance); XR_FAILED(r)) return r;
    return TwoCall(capacity, count, modes, 1, [](XrEnvironmentBlendMode& m, uint32_t) {
        m = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
    });
}

XrResult XRAPI_CALL ConvertTimespecTimeToTime(XrInstance handle, const timespec* ts, XrTime* time) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstance(handle, &instance); XR_FAILED(r)) return r;
    if (!ts || !time) return XR_ERROR_VALIDATION_FAILURE;
    *time = XrTime(ts->tv_sec) * 1000000000 + ts->tv_nsec;  // XrTime is CLOCK_MONOTONIC ns
    return XR_SUCCESS;
}

XrResult XRAPI_CALL ConvertTimeToTimespecTime(XrInstance handle, XrTime time, timespec* ts) {
    auto lock = LockApi();
    Instance* instance = nullptr;
    if (XrResult r = CheckInstance(handle, &instance); XR_FAILED(r)) return r;
    if (!ts) return XR_ERROR_VALIDATION_FAILURE;
    if (time <= 0) return XR_ERROR_TIME_INVALID;
    ts->tv_sec = time / 1000000000;
    ts->tv_nsec = time % 1000000000;
    return XR_SUCCESS;
}

}  // namespace

XrResult CheckSystem(const Instance& instance, XrSystemId id) {
    return id == kSystemId && instance.systemQueried ? XR_SUCCESS : XR_ERROR_SYSTEM_INVALID;
}

XrResult CheckInstanceSystem(XrInstance handle, XrSystemId id, Instance** out) {
    if (XrResult r = CheckInstance(handle, out); XR_FAILED(r)) return r;
    return CheckSystem(**out, id);
}

void AddInstanceFunctions(ApiTable& t) {
    t.insert(t.end(), {
        XRRT_CORE(EnumerateInstanceExtensionProperties), XRRT_CORE(EnumerateApiLayerProperties),
        XRRT_CORE(CreateInstance), XRRT_CORE(DestroyInstance), XRRT_CORE(GetInstanceProperties),
        XRRT_CORE(PollEvent), XRRT_CORE(ResultToString), XRRT_CORE(StructureTypeToString),
        XRRT_CORE(StringToPath), XRRT_CORE(PathToString), XRRT_CORE(GetSystem),
        XRRT_CORE(GetSystemProperties), XRRT_CORE(EnumerateViewConfigurations),
        XRRT_CORE(GetViewConfigurationProperties), XRRT_CORE(EnumerateViewConfigurationViews),
        XRRT_CORE(EnumerateEnvironmentBlendModes)
    });
    t.push_back({"xrConvertTimespecTimeToTimeKHR", Fn(&ConvertTimespecTimeToTime),
                 XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME});
    t.push_back({"xrConvertTimeToTimespecTimeKHR", Fn(&ConvertTimeToTimespecTime),
                 XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME});
}

}  // namespace fovrt::xrrt
