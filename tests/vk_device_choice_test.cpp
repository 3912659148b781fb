// Device resolution: one meaning of auto / vulkan / cpu / <index> for every command, the preferred
// device, and one-line errors naming denoise.device, the valid forms and the devices present.
#include "core/error.h"
#include "test_support.h"
#include "vk/context.h"
#include "vk/device_choice.h"

using namespace fovrt;

namespace {

VulkanDeviceInfo Device(uint32_t index, const char* type, bool compute = true) {
    return {index, std::string("dev-") + type, type, compute};
}

std::string ErrorOf(const std::string& device, const std::vector<VulkanDeviceInfo>& devices) {
    try {
        ResolveVulkanDevice(device, devices);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("device settings: the four forms parse, nothing else does", "[vk]") {
    CHECK(ParseDeviceSetting("auto")->kind == DeviceSetting::Kind::Auto);
    CHECK(ParseDeviceSetting("vulkan")->kind == DeviceSetting::Kind::Vulkan);
    CHECK(ParseDeviceSetting("cpu")->kind == DeviceSetting::Kind::Cpu);
    CHECK(ParseDeviceSetting("0")->kind == DeviceSetting::Kind::Index);
    CHECK(ParseDeviceSetting("12")->index == 12);
    for (const char* bad : {"", "gpu0", "-1", "+1", " 1", "1 ", "0x1", "Auto", "99999999999"})
        CHECK_FALSE(ParseDeviceSetting(bad));
}

TEST_CASE("the preferred device: discrete, then integrated, then any; first of a type; compute only", "[vk]") {
    CHECK(PreferredVulkanDevice({}) == std::nullopt);
    CHECK(PreferredVulkanDevice({Device(0, "cpu"), Device(1, "integrated"), Device(2, "discrete")}) == 2u);
    CHECK(PreferredVulkanDevice({Device(0, "cpu"), Device(1, "integrated"), Device(2, "integrated")}) == 1u);
    CHECK(PreferredVulkanDevice({Device(0, "cpu"), Device(1, "virtual")}) == 0u);
    CHECK(PreferredVulkanDevice({Device(0, "discrete", false), Device(1, "cpu")}) == 1u);
    CHECK(PreferredVulkanDevice({Device(0, "discrete", false)}) == std::nullopt);
}

TEST_CASE("auto and vulkan resolve to the same device; cpu and an index as written", "[vk]") {
    const std::vector<VulkanDeviceInfo> devices = {Device(0, "cpu"), Device(1, "discrete")};
    const DeviceDecision autoChoice = ResolveVulkanDevice("auto", devices);
    const DeviceDecision vulkanChoice = ResolveVulkanDevice("vulkan", devices);
    CHECK(autoChoice.vulkan);
    CHECK(vulkanChoice.vulkan);
    CHECK(autoChoice.index == 1);
    CHECK(vulkanChoice.index == 1);
    CHECK(autoChoice.options.device == "1");
    CHECK(vulkanChoice.options.device == "1");
    CHECK(autoChoice.notice.empty());

    const DeviceDecision zero = ResolveVulkanDevice("0", devices);
    CHECK(zero.vulkan);
    CHECK(zero.index == 0);
    CHECK(zero.options.device == "0");

    const DeviceDecision cpu = ResolveVulkanDevice("cpu", devices);
    CHECK_FALSE(cpu.vulkan);
    CHECK(cpu.notice.empty());
}

TEST_CASE("without a Vulkan device: auto falls back with one notice line, vulkan is an error", "[vk]") {
    const DeviceDecision autoChoice = ResolveVulkanDevice("auto", {});
    CHECK_FALSE(autoChoice.vulkan);
    CHECK(autoChoice.notice.find("C++ reference") != std::string::npos);
    CHECK(autoChoice.notice.find('\n') == std::string::npos);
    CHECK_FALSE(ResolveVulkanDevice("cpu", {}).vulkan);
    const std::string vulkan = ErrorOf("vulkan", {});
    CHECK(vulkan.find("denoise.device") != std::string::npos);
    CHECK(vulkan.find("devices present: none") != std::string::npos);
    // A device without a compute queue is no device for the denoisers.
    CHECK_FALSE(ResolveVulkanDevice("auto", {Device(0, "discrete", false)}).vulkan);
}

TEST_CASE("a bad device is one line naming the key, the valid forms and the devices present", "[vk]") {
    const std::vector<VulkanDeviceInfo> devices = {Device(0, "cpu")};
    for (const char* bad : {"7", "banana", "gpu0", ""}) {
        const std::string what = ErrorOf(bad, devices);
        CAPTURE(bad, what);
        CHECK(what.find("denoise.device = \"" + std::string(bad) + "\"") != std::string::npos);
        CHECK(what.find(kDeviceSettingForms) != std::string::npos);
        CHECK(what.find("devices present: 0: dev-cpu (cpu)") != std::string::npos);
        CHECK(what.find('\n') == std::string::npos);
    }
    CHECK(ErrorOf("7", devices).find("no Vulkan device 7") != std::string::npos);
}

TEST_CASE("on this machine, auto and vulkan create a context on the same device", "[vk][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    const DeviceDecision autoChoice = ResolveVulkanDevice("auto");
    const DeviceDecision vulkanChoice = ResolveVulkanDevice("vulkan");
    REQUIRE(autoChoice.vulkan);
    REQUIRE(vulkanChoice.vulkan);
    CHECK(autoChoice.index == vulkanChoice.index);
    CHECK(autoChoice.index == PreferredVulkanDevice(VulkanContext::ListDevices()));
    VulkanContextOptions o;
    o.validation = Validation::Off;
    o.device = "auto";
    const std::string autoName = VulkanContext::Create(o).deviceName();
    o.device = "vulkan";
    CHECK(VulkanContext::Create(o).deviceName() == autoName);
    o.device = std::to_string(autoChoice.index);
    CHECK(VulkanContext::Create(o).deviceName() == autoName);
    // cpu means the C++ reference, which has no Vulkan context.
    o.device = "cpu";
    CHECK_THROWS_WITH(VulkanContext::Create(o), Catch::Contains("denoise.device"));
}
