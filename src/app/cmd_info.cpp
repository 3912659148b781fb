// `fovrt info`: versions of fovrt and the libraries it was built with, the Vulkan devices the
// loader reports (the indices `--set denoise.device=<index>` accepts), the CPU thread count and model, and
// the denoiser variants with one line each (denoise/variants.cpp).
#include <algorithm>
#include <cstdio>
#include <thread>

#include "app/commands.h"
#include "denoise/variants.h"
#include "pipeline/build_info.h"
#include "vk/context.h"

namespace fovrt {

void RegisterInfoCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("info", "Print versions, Vulkan devices and build settings");
    cmd->callback([] {
        const nlohmann::json build = BuildInfoJson();  // items() must not outlive its object
        for (const auto& [key, value] : build.items())
            std::printf("%-16s %s\n", key.c_str(), value.get<std::string>().c_str());
        std::printf("%-16s %u\n", "cpu threads", std::thread::hardware_concurrency());
        std::printf("%-16s %s\n", "machine", FormatCpu(DescribeCpu()).c_str());  // the benchmark scripts' header
        auto devices = VulkanContext::ListDevices();
        if (devices.empty()) std::printf("vulkan devices   none (denoisers fall back to the C++ reference)\n");
        for (const VulkanDeviceInfo& d : devices)
            std::printf("vulkan device %u  %s (%s)\n", d.index, d.name.c_str(), d.type.c_str());
        int nameWidth = 0;  // the names in one column, as wide as the longest
        for (const DenoiserVariant& v : DenoiserVariants()) nameWidth = std::max(nameWidth, int(v.name.size()));
        for (const DenoiserVariant& v : DenoiserVariants())  // the names denoise.denoisers accepts
            std::printf("denoiser         %-*.*s %.*s\n", nameWidth, int(v.name.size()), v.name.data(),
                        int(v.summary.size()), v.summary.data());
    });
}

}  // namespace fovrt
