// The one meaning of the denoise device setting (`denoise.device`, `bench --denoisers --device`),
// shared by every command and by the denoiser factory:
//   auto     the preferred Vulkan device (PreferredVulkanDevice); the C++ reference, with a
//            one-line notice, when no Vulkan device exists
//   vulkan   the same device as auto, but an error when no Vulkan device exists
//   cpu      the C++ reference; no Vulkan
//   <index>  the Vulkan device of that index, as `fovrt info` lists them
// Reads: the devices the Vulkan loader reports. Writes: nothing (creates no context).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vk/context.h"

namespace fovrt {

// The valid forms, for messages.
inline constexpr const char* kDeviceSettingForms = "auto, vulkan, cpu or a Vulkan device index";

struct DeviceSetting {
    enum class Kind { Auto, Vulkan, Cpu, Index };
    Kind kind = Kind::Auto;
    uint32_t index = 0;  // Kind::Index only
};

// The setting a string names, or nullopt when it is none of kDeviceSettingForms (syntax only:
// config validation uses it without touching Vulkan).
std::optional<DeviceSetting> ParseDeviceSetting(const std::string& device);

// The device auto and vulkan pick: the first discrete GPU, else the first integrated GPU, else the
// first device of any type; devices without a compute queue never. nullopt when none qualifies.
std::optional<uint32_t> PreferredVulkanDevice(const std::vector<VulkanDeviceInfo>& devices);

struct DeviceDecision {
    bool vulkan = false;           // false: denoise with the C++ reference
    uint32_t index = 0;            // vulkan: the chosen device
    VulkanContextOptions options;  // vulkan: options.device = that index, never "auto"
    std::string notice;            // one line for stderr (auto without a Vulkan device), or empty
};

// Resolves a setting against the devices present. A malformed value, an index past the last
// device, or vulkan without a device is a fovrt::Error naming denoise.device, the valid forms and
// the devices present.
DeviceDecision ResolveVulkanDevice(const std::string& device);
// The same against a given device list (tests: machines with and without devices).
DeviceDecision ResolveVulkanDevice(const std::string& device, const std::vector<VulkanDeviceInfo>& devices);

// "0: llvmpipe (cpu), 1: …", or "none".
std::string DescribeVulkanDevices(const std::vector<VulkanDeviceInfo>& devices);

}  // namespace fovrt
