#include "vk/device_choice.h"

#include <algorithm>
#include <cctype>
#include <charconv>

#include <fmt/format.h>

#include "core/error.h"

namespace fovrt {

std::optional<DeviceSetting> ParseDeviceSetting(const std::string& device) {
    if (device == "auto") return DeviceSetting{DeviceSetting::Kind::Auto, 0};
    if (device == "vulkan") return DeviceSetting{DeviceSetting::Kind::Vulkan, 0};
    if (device == "cpu") return DeviceSetting{DeviceSetting::Kind::Cpu, 0};
    // Digits only: no sign, no spaces, no hex, so "1" is the one spelling of device 1.
    if (device.empty() || !std::all_of(device.begin(), device.end(),
                                       [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
        return std::nullopt;
    uint32_t index = 0;
    const auto [end, error] = std::from_chars(device.data(), device.data() + device.size(), index);
    if (error != std::errc() || end != device.data() + device.size()) return std::nullopt;
    return DeviceSetting{DeviceSetting::Kind::Index, index};
}

std::optional<uint32_t> PreferredVulkanDevice(const std::vector<VulkanDeviceInfo>& devices) {
    auto score = [](const VulkanDeviceInfo& d) { return d.type == "discrete" ? 3 : d.type == "integrated" ? 2 : 1; };
    std::optional<uint32_t> pick;
    int best = 0;
    for (const VulkanDeviceInfo& d : devices)
        if (d.compute && score(d) > best) {  // strict: the first of the best type wins
            best = score(d);
            pick = d.index;
        }
    return pick;
}

std::string DescribeVulkanDevices(const std::vector<VulkanDeviceInfo>& devices) {
    std::string list;
    for (const VulkanDeviceInfo& d : devices)
        list += fmt::format("{}{}: {} ({})", list.empty() ? "" : ", ", d.index, d.name, d.type);
    return list.empty() ? std::string("none") : list;
}

DeviceDecision ResolveVulkanDevice(const std::string& device, const std::vector<VulkanDeviceInfo>& devices) {
    auto fail = [&](const std::string& why) {
        Fail("denoise.device = \"{}\": {} (expected {}; Vulkan devices present: {})", device, why,
             kDeviceSettingForms, DescribeVulkanDevices(devices));
    };
    const std::optional<DeviceSetting> setting = ParseDeviceSetting(device);
    if (!setting) fail("not a device setting");
    DeviceDecision decision;
    switch (setting->kind) {
        case DeviceSetting::Kind::Cpu:
            return decision;
        case DeviceSetting::Kind::Auto:
        case DeviceSetting::Kind::Vulkan: {
            const std::optional<uint32_t> pick = PreferredVulkanDevice(devices);
            if (!pick) {
                if (setting->kind == DeviceSetting::Kind::Vulkan) fail("no Vulkan device with a compute queue");
                decision.notice = "fovrt: notice: no Vulkan device; denoising with the C++ reference (cpu)";
                return decision;
            }
            decision.index = *pick;
            break;
        }
        case DeviceSetting::Kind::Index: {
            const bool present = std::any_of(devices.begin(), devices.end(),
                                             [&](const VulkanDeviceInfo& d) { return d.index == setting->index; });
            if (!present) fail(fmt::format("no Vulkan device {}", setting->index));
            decision.index = setting->index;
            break;
        }
    }
    decision.vulkan = true;
    decision.options.device = std::to_string(decision.index);
    return decision;
}

DeviceDecision ResolveVulkanDevice(const std::string& device) {
    if (device == "cpu") return {};  // no need to ask the loader (nor to have one)
    return ResolveVulkanDevice(device, VulkanContext::ListDevices());
}

}  // namespace fovrt
