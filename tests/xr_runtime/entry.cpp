// Loader negotiation and xrGetInstanceProcAddr: the only symbol this library exports is
// xrNegotiateLoaderRuntimeInterface (the loader dlsym()s it from the manifest's library_path);
// everything else is reached through the function table. Also the small helpers every file shares.
#include <cmath>
#include <cstdio>
#include <string_view>
#include <unordered_map>

#include "runtime.h"

namespace fovrt::xrrt {

Runtime& TheRuntime() {
    static Runtime runtime;
    return runtime;
}

XrResult CheckInstance(XrInstance handle, Instance** out) {
    Instance* instance = Find(TheRuntime().instances, handle);
    if (!instance) return XR_ERROR_HANDLE_INVALID;
    if (instance->lost) return XR_ERROR_INSTANCE_LOST;
    *out = instance;
    return XR_SUCCESS;
}

XrResult CheckSession(XrSession handle, Session** out) {
    Session* session = Find(TheRuntime().sessions, handle);
    if (!session) return XR_ERROR_HANDLE_INVALID;
    if (session->instance->lost) return XR_ERROR_INSTANCE_LOST;
    *out = session;
    return XR_SUCCESS;
}

XrResult CheckSessionAndGate(XrSession handle, Session** out) {
    if (XrResult r = CheckSession(handle, out); XR_FAILED(r)) return r;
    return SessionGate(**out);
}

XrTime Now() {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return XrTime(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

void Log(const std::string& message) { std::fprintf(stderr, "fovrt test runtime: %s\n", message.c_str()); }

XrResult TwoCallString(uint32_t capacity, uint32_t* count, char* out, const std::string& value) {
    if (!count) return XR_ERROR_VALIDATION_FAILURE;
    *count = uint32_t(value.size() + 1);
    if (capacity == 0) return XR_SUCCESS;
    if (capacity < *count) return XR_ERROR_SIZE_INSUFFICIENT;
    if (!out) return XR_ERROR_VALIDATION_FAILURE;
    std::memcpy(out, value.c_str(), value.size() + 1);
    return XR_SUCCESS;
}

bool IsUnitQuaternion(const XrQuaternionf& q) {
    float norm2 = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
    return std::isfinite(norm2) && std::fabs(norm2 - 1.0f) < 1e-2f;
}

Pose FromXr(const XrPosef& pose) {
    Pose p;
    p.orientation = glm::quat(pose.orientation.w, pose.orientation.x, pose.orientation.y,
                              pose.orientation.z);
    p.position = glm::vec3(pose.position.x, pose.position.y, pose.position.z);
    return p;
}

XrPosef ToXr(const Pose& pose) {
    XrPosef p{};
    p.orientation = {pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w};
    p.position = {pose.position.x, pose.position.y, pose.position.z};
    return p;
}

namespace {

struct TableEntry {
    PFN_xrVoidFunction function;
    const char* extension;
};

const std::unordered_map<std::string_view, TableEntry>& FunctionTable() {
    static const auto table = [] {
        ApiTable list;
        AddInstanceFunctions(list);
        AddVulkanFunctions(list);
        AddSessionFunctions(list);
        AddSpaceFunctions(list);
        AddSwapchainFunctions(list);
        AddActionFunctions(list);
        std::unordered_map<std::string_view, TableEntry> map;
        for (const ApiFunction& f : list) map[f.name] = {f.function, f.extension};
        return map;
    }();
    return table;
}

XrResult XRAPI_CALL GetInstanceProcAddr(XrInstance instanceHandle, const char* name,
                                        PFN_xrVoidFunction* function) {
    if (!name || !function) return XR_ERROR_VALIDATION_FAILURE;
    *function = nullptr;
    std::string_view n(name);
    if (n == "xrGetInstanceProcAddr") {
        *function = Fn(&GetInstanceProcAddr);
        return XR_SUCCESS;
    }
    const auto& table = FunctionTable();
    auto it = table.find(n);
    if (instanceHandle == XR_NULL_HANDLE) {
        // Only these may be asked for before an instance exists.
        bool global = n == "xrEnumerateInstanceExtensionProperties" ||
                      n == "xrEnumerateApiLayerProperties" || n == "xrCreateInstance";
        if (!global) return XR_ERROR_HANDLE_INVALID;
        if (it == table.end()) return XR_ERROR_FUNCTION_UNSUPPORTED;
        *function = it->second.function;
        return XR_SUCCESS;
    }
    {
        auto lock = LockApi();
        if (!Find(TheRuntime().instances, instanceHandle)) return XR_ERROR_HANDLE_INVALID;
        if (it == table.end()) return XR_ERROR_FUNCTION_UNSUPPORTED;
        auto* instance = Find(TheRuntime().instances, instanceHandle);
        if (it->second.extension && !instance->Enabled(it->second.extension))
            return XR_ERROR_FUNCTION_UNSUPPORTED;
    }
    *function = it->second.function;
    return XR_SUCCESS;
}

// The loader's negotiation structures (loader_interfaces.h in the OpenXR SDK, which Debian's
// libopenxr-dev does not install): same layout and values.
constexpr int kStructLoaderInfo = 1;
constexpr int kStructRuntimeRequest = 3;
constexpr uint32_t kLoaderInfoVersion = 1;
constexpr uint32_t kRuntimeInfoVersion = 1;
constexpr uint32_t kRuntimeInterfaceVersion = 1;

struct NegotiateLoaderInfo {
    int structType;
    uint32_t structVersion;
    size_t structSize;
    uint32_t minInterfaceVersion;
    uint32_t maxInterfaceVersion;
    XrVersion minApiVersion;
    XrVersion maxApiVersion;
};

struct NegotiateRuntimeRequest {
    int structType;
    uint32_t structVersion;
    size_t structSize;
    uint32_t runtimeInterfaceVersion;
    XrVersion runtimeApiVersion;
    PFN_xrGetInstanceProcAddr getInstanceProcAddr;
};

}  // namespace
}  // namespace fovrt::xrrt

extern "C" __attribute__((visibility("default"))) XrResult XRAPI_CALL
xrNegotiateLoaderRuntimeInterface(const fovrt::xrrt::NegotiateLoaderInfo* loaderInfo,
                                  fovrt::xrrt::NegotiateRuntimeRequest* runtimeRequest) {
    using namespace fovrt::xrrt;
    if (!loaderInfo || !runtimeRequest || loaderInfo->structType != kStructLoaderInfo ||
        loaderInfo->structVersion != kLoaderInfoVersion ||
        loaderInfo->structSize != sizeof(NegotiateLoaderInfo) ||
        runtimeRequest->structType != kStructRuntimeRequest ||
        runtimeRequest->structVersion != kRuntimeInfoVersion ||
        runtimeRequest->structSize != sizeof(NegotiateRuntimeRequest))
        return XR_ERROR_INITIALIZATION_FAILED;
    if (loaderInfo->minInterfaceVersion > kRuntimeInterfaceVersion ||
        loaderInfo->maxInterfaceVersion < kRuntimeInterfaceVersion)
        return XR_ERROR_INITIALIZATION_FAILED;
    if (XR_VERSION_MAJOR(loaderInfo->maxApiVersion) < 1 ||
        XR_VERSION_MAJOR(loaderInfo->minApiVersion) > 1)
        return XR_ERROR_INITIALIZATION_FAILED;
    runtimeRequest->runtimeInterfaceVersion = kRuntimeInterfaceVersion;
    runtimeRequest->runtimeApiVersion = XR_CURRENT_API_VERSION;
    runtimeRequest->getInstanceProcAddr = &GetInstanceProcAddr;
    return XR_SUCCESS;
}
