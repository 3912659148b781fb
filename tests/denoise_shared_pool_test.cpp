// The transient pool and staging ring shared by every denoiser on one Vulkan device
// (vk/shared_buffers.h): both eyes and several variants taking turns with one set of slots give,
// byte for byte, what each gives with slots of its own; the device holds what the memory plan of
// the device says (AddDenoiserOnDevice); a plane of the shared slots is refused once another
// denoiser's frame has reused them; the slots are freed with their last user.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "denoise/denoiser_factory.h"
#include "denoise/memory_plan.h"
#include "denoise/vulkan/svgf_family_vk.h"
#include "denoise_svgf_scenes.h"
#include "test_support.h"
#include "vk/shared_buffers.h"
#include "vk_test_support.h"

using namespace fovrt;
using test::TestContext;

namespace {

constexpr int kWidth = 48, kHeight = 40, kFrames = 4;

// The inputs of one eye: the two eyes see different frames, as a headset's do.
FrameInputs EyeFrame(int eye, uint32_t frame) {
    return test::RandomTwoHistoryFrame(kWidth, kHeight, frame + 100u * uint32_t(eye), eye == 1);
}

struct Instance {
    const char* variant;
    int eye;
};

// Every frame of one instance, run while no other denoiser lives on `context`: its slots are its own.
std::vector<Plane<vec3>> RunAlone(const std::shared_ptr<VulkanContext>& context, const Instance& instance,
                                  const DenoiserParams& params) {
    SvgfFamilyVulkanDenoiser d(FindDenoiserVariant(instance.variant), context, params);
    std::vector<Plane<vec3>> out(kFrames);
    for (uint32_t t = 0; t < kFrames; ++t) d.Denoise(EyeFrame(instance.eye, t), out[t]);
    return out;
}

}  // namespace

TEST_CASE("both eyes and several variants take turns with one transient pool, each as if alone", "[vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto ctx = TestContext();
    // svgf first: two-history's larger plan grows the slots svgf's descriptor sets name.
    const std::vector<Instance> instances = {
        {"svgf", 0}, {"svgf", 1}, {"two-history", 0}, {"two-history", 1}, {"two-history-asvgf-stable-antilag", 0}};
    for (Precision precision : {Precision::Fp32, Precision::Fp16}) {
        if (precision == Precision::Fp16 && !ctx->supports16BitStorage()) continue;
        INFO((precision == Precision::Fp16 ? "fp16" : "fp32"));
        DenoiserParams params;
        params.precision = precision;
        std::vector<std::vector<Plane<vec3>>> alone;
        for (const Instance& instance : instances) alone.push_back(RunAlone(ctx, instance, params));

        const size_t before = ctx->allocator().LiveBytes();
        std::vector<std::unique_ptr<SvgfFamilyVulkanDenoiser>> together;
        std::vector<BufferPlan> device;
        for (const Instance& instance : instances) {
            together.push_back(std::make_unique<SvgfFamilyVulkanDenoiser>(FindDenoiserVariant(instance.variant), ctx, params));
            AddDenoiserOnDevice(device, std::string(instance.variant) + ".eye" + std::to_string(instance.eye) + ".",
                                PlanDenoiserMemory(instance.variant, kWidth, kHeight,
                                                   ParamsForDenoiser(instance.variant, params)));
        }
        const uint64_t generation = ctx->SharedDeviceBuffers()->generation();
        Plane<vec3> out;
        for (uint32_t t = 0; t < kFrames; ++t)
            for (size_t i = 0; i < instances.size(); ++i) {
                INFO(instances[i].variant << " eye " << instances[i].eye << " frame " << t);
                together[i]->Denoise(EyeFrame(instances[i].eye, t), out);
                REQUIRE(out.size() == alone[i][t].size());
                CHECK(std::memcmp(out.data(), alone[i][t].data(), out.bytes()) == 0);
            }
        // The slots grew as larger plans arrived, and the device holds what its plan says: each
        // denoiser's own buffers, the shared ones once at their largest user's size.
        CHECK(ctx->SharedDeviceBuffers()->generation() > generation);
        CHECK(ctx->allocator().LiveBytes() - before == TotalBytes(device));
        size_t separate = 0;
        for (const Instance& instance : instances)
            separate += TotalBytes(PlanDenoiserMemory(instance.variant, kWidth, kHeight,
                                                      ParamsForDenoiser(instance.variant, params)));
        CHECK(TotalBytes(device) < separate);
        together.clear();
        CHECK(ctx->allocator().LiveBytes() == before);  // the shared slots went with their last user
    }
    CHECK(ctx->validationErrors() == 0);
}

TEST_CASE("a plane in the shared slots is refused once another denoiser's frame has reused them", "[vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    auto ctx = TestContext();
    DenoiserParams params;
    SvgfFamilyVulkanDenoiser left(FindDenoiserVariant("two-history"), ctx, params);
    SvgfFamilyVulkanDenoiser right(FindDenoiserVariant("two-history"), ctx, params);
    Plane<vec3> out;
    left.Denoise(EyeFrame(0, 0), out);
    right.Denoise(EyeFrame(1, 0), out);
    left.Denoise(EyeFrame(0, 1), out);  // a frame with a previous one: q is not 0 everywhere
    // q, the blend's gradient factor (a debug view), lives in a transient slot until the frame ends.
    REQUIRE(left.Readable("q"));
    const std::vector<uint8_t> q = left.ReadBuffer("q");
    REQUIRE(q != std::vector<uint8_t>(q.size(), 0));
    right.Denoise(EyeFrame(1, 1), out);
    CHECK_FALSE(left.Readable("q"));
    CHECK_THROWS_WITH(left.ReadBuffer("q"), Catch::Contains("another denoiser on the device has run a frame"));
    CHECK(right.Readable("q"));
    CHECK(right.ReadBuffer("q") != q);  // the slot now holds the right eye's
    // Histories are each denoiser's own.
    const std::string length = "direct.length." + left.LastWrittenSide();
    CHECK(left.Readable(length));
    CHECK(left.ReadBuffer(length).size() == size_t(kWidth) * kHeight * sizeof(float));
    CHECK(ctx->validationErrors() == 0);
}

TEST_CASE("the device's memory plan counts the shared slots once, at the largest user's size") {
    DenoiserParams params;
    const std::vector<BufferPlan> svgf = PlanDenoiserMemory("svgf", 64, 32, params);
    const std::vector<BufferPlan> two = PlanDenoiserMemory("two-history", 64, 32, params);
    std::vector<BufferPlan> device;
    AddDenoiserOnDevice(device, "a.", svgf);
    AddDenoiserOnDevice(device, "b.", two);
    AddDenoiserOnDevice(device, "c.", svgf);
    size_t own = 0, shared = 0;
    std::map<std::string, size_t> largest;
    for (const auto* plan : {&svgf, &two, &svgf})
        for (const BufferPlan& b : *plan) {
            if (b.shared)
                largest[b.name] = std::max(largest[b.name], b.bytes);
            else
                own += b.bytes;
        }
    for (const auto& [name, bytes] : largest) shared += bytes;
    REQUIRE(largest.count("staging") == 1);  // the staging ring is shared too
    REQUIRE(largest.count("transient.0") == 1);
    CHECK(TotalBytes(device) == own + shared);
    for (const BufferPlan& b : device)
        if (b.shared) CHECK(b.name.rfind("shared.", 0) == 0);
        else CHECK((b.name.rfind("a.", 0) == 0 || b.name.rfind("b.", 0) == 0 || b.name.rfind("c.", 0) == 0));
}
