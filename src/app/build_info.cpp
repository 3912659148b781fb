#include "app/build_info.h"

#include <OpenEXR/OpenEXRConfig.h>
#include <embree3/rtcore.h>
#include <tbb/version.h>
#include <vulkan/vulkan.h>

#include <fmt/format.h>

namespace fovrt {

nlohmann::json BuildInfoJson() {
    nlohmann::json info;
    info["fovrt"] = FOVRT_VERSION;
#ifdef NDEBUG
    info["build_type"] = "Release";
#else
    info["build_type"] = "Debug";
#endif
    info["compiler"] = fmt::format("{} {}",
#if defined(__clang__)
                                   "clang", __clang_version__
#else
                                   "gcc", __VERSION__
#endif
    );
    info["embree"] = fmt::format("{}.{}.{}", RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH);
    info["tbb"] = fmt::format("{}.{}", TBB_VERSION_MAJOR, TBB_VERSION_MINOR);
    info["vulkan_headers"] = fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(VK_HEADER_VERSION_COMPLETE),
                                         VK_API_VERSION_MINOR(VK_HEADER_VERSION_COMPLETE),
                                         VK_HEADER_VERSION);
    info["openexr"] = OPENEXR_VERSION_STRING;
    return info;
}

}  // namespace fovrt
