// `fovrt info`: versions of fovrt and of the libraries it was built with.
#include <cstdio>

#include <embree3/rtcore.h>
#include <vulkan/vulkan.h>

#include "commands.h"

namespace fovrt {

void RegisterInfoCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("info", "Print versions, devices and build settings");
    cmd->callback([] {
        std::printf("fovrt %s\n", FOVRT_VERSION);
        std::printf("embree %d.%d.%d\n", RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH);
        std::printf("vulkan headers %d.%d.%d\n", VK_API_VERSION_MAJOR(VK_HEADER_VERSION_COMPLETE),
                    VK_API_VERSION_MINOR(VK_HEADER_VERSION_COMPLETE), VK_HEADER_VERSION);
    });
}

}  // namespace fovrt
