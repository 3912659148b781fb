// denoise.device through the commands' paths (config, DenoiserSet, the denoiser factory): every
// path resolves auto and vulkan to the same device, cpu to the C++ reference, and rejects a bad
// value with one line naming denoise.device.
#include "config/config.h"
#include "config/config_cli.h"
#include "core/error.h"
#include "denoise/denoiser_factory.h"
#include "denoise/pass_plan.h"
#include "denoise/vulkan/svgf_family_vk.h"
#include "pipeline/denoiser_set.h"
#include "test_support.h"
#include "vk/device_choice.h"

using namespace fovrt;

namespace {

RunConfig WithDevice(const std::string& device) {
    ConfigOptions options;
    options.sets = {"denoise.device=\"" + device + "\""};
    return ResolveConfig(options);
}

std::string SetDeviceName(const std::string& device) {
    DenoiseConfig config = WithDevice(device).denoise;
    config.denoisers = {"svgf"};
    return DenoiserSet(config).DeviceDescription();
}

std::string FactoryDeviceName(const std::string& device) {
    auto denoiser = CreateDenoiser("svgf", device, DenoiserParams{});
    auto* vk = dynamic_cast<SvgfFamilyVulkanDenoiser*>(denoiser.get());
    return vk ? vk->context().deviceName() : "cpu";
}

}  // namespace

TEST_CASE("config accepts the four device forms and names denoise.device for anything else", "[app]") {
    for (const char* device : {"auto", "vulkan", "cpu", "0"}) CHECK(WithDevice(device).denoise.device == device);
    CHECK_THROWS_WITH(WithDevice("gpu0"), Catch::Contains("denoise.device") && Catch::Contains(kDeviceSettingForms) &&
                                              Catch::Contains("devices present: "));
}

TEST_CASE("cpu is the C++ reference on every path", "[app]") {
    CHECK(SetDeviceName("cpu") == "cpu (C++ reference)");
    CHECK(FactoryDeviceName("cpu") == "cpu");
}

TEST_CASE("auto and vulkan are the same device for DenoiserSet and the factory", "[app][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    const std::string autoSet = SetDeviceName("auto");
    CHECK(autoSet.rfind("vulkan (", 0) == 0);
    CHECK(SetDeviceName("vulkan") == autoSet);
    CHECK(SetDeviceName(std::to_string(ResolveVulkanDevice("auto").index)) == autoSet);
    const std::string autoFactory = FactoryDeviceName("auto");
    CHECK(autoSet == "vulkan (" + autoFactory + ")");
    CHECK(FactoryDeviceName("vulkan") == autoFactory);
}

TEST_CASE("a device index past the last device fails before any work, naming the key", "[app][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    DenoiseConfig config = WithDevice("99").denoise;
    CHECK_THROWS_WITH(DenoiserSet(config), Catch::Contains("denoise.device = \"99\"") &&
                                               Catch::Contains("devices present: 0:"));
    CHECK_THROWS_WITH(CreateDenoiser("svgf", "99", DenoiserParams{}), Catch::Contains("denoise.device"));
}

// denoise.precision = auto (the default): fp16 storage for the SVGF family on a GPU with 16-bit
// storage, fp32 on a CPU device, without 16-bit storage, for the C++ reference and for the RAE.
TEST_CASE("precision auto resolves by device and family, and an explicit precision stays", "[app]") {
    CHECK(DefaultConfig().denoise.params.precision == Precision::Auto);
    const DenoiserVariant& svgf = FindDenoiserVariant("svgf");
    const DenoiserVariant& two = FindDenoiserVariant("two-history-asvgf-stable-antilag");
    const DenoiserVariant& rae = FindDenoiserVariant("rae");
    const PrecisionTarget reference{}, gpu{true, false, true}, lavapipe{true, true, true}, gpuNo16{true, false, false};
    for (const DenoiserVariant* v : {&svgf, &two}) {
        CHECK(ResolvePrecision(Precision::Auto, *v, gpu) == Precision::Fp16);
        CHECK(ResolvePrecision(Precision::Auto, *v, lavapipe) == Precision::Fp32);
        CHECK(ResolvePrecision(Precision::Auto, *v, gpuNo16) == Precision::Fp32);
        CHECK(ResolvePrecision(Precision::Auto, *v, reference) == Precision::Fp32);
    }
    CHECK(ResolvePrecision(Precision::Auto, rae, gpu) == Precision::Fp32);
    for (const PrecisionTarget& t : {reference, gpu, lavapipe, gpuNo16})
        for (Precision p : {Precision::Fp32, Precision::Fp16}) CHECK(ResolvePrecision(p, svgf, t) == p);
    CHECK(PlannedPrecisionTarget("cpu").vulkan == false);
    // A plan has one storage: auto reaching it unresolved is refused.
    DenoiserParams unresolved;
    unresolved.precision = Precision::Auto;
    CHECK_THROWS_WITH(BuildDenoiserPlan("svgf", unresolved, 8, 8), Catch::Contains("auto is not resolved"));
}

TEST_CASE("a run's memory plan and its denoisers resolve auto for the same device", "[app][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    RunConfig config = WithDevice("auto");
    config.denoise.denoisers = {"svgf", "rae"};
    const VulkanContext context = VulkanContext::Create();
    const PrecisionTarget planned = PlannedPrecisionTarget("auto");
    const PrecisionTarget actual = PrecisionTargetOf(&context);
    CHECK(planned.vulkan);
    CHECK(planned.cpuDevice == actual.cpuDevice);
    CHECK(planned.storage16 == actual.storage16);  // the device list reports what the device has
    const Precision svgf = ResolvePrecision(Precision::Auto, FindDenoiserVariant("svgf"), actual);
    CHECK(RunDenoiserParams(config, "svgf").precision == svgf);
    CHECK(RunDenoiserParams(config, "rae").precision == Precision::Fp32);
    DenoiserSet set(config.denoise);
    CHECK(set.StorageDescription() ==
          (svgf == Precision::Fp16 ? std::string("fp16 (rae: fp32)") : std::string("fp32")));
}
