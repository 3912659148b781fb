// Vulkan runtime: context creation, device selection errors, allocator accounting, staging
// upload/download, a dispatch with push constants, timestamps, zero validation errors.
#include <array>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "denoise/vulkan/svgf_layout.h"
#include "denoise/vulkan/svgf_texel_formats.h"
#include "shaders/shader_registry.h"
#include "test_support.h"
#include "vk/context.h"
#include "vk/pipeline.h"
#include "vk/recorder.h"
#include "vk/transfer_ring.h"
#include "vk/vk_check.h"

using namespace fovrt;

namespace {
VulkanContextOptions TestOptions() {
    VulkanContextOptions o;
    o.validation = Validation::On;  // falls back with a notice when the layer is absent
    return o;
}
}  // namespace

TEST_CASE("shader registry embeds every stage in both precisions", "[vk]") {
    // *_pair: the two-channel variants (FOVRT_CHANNELS 2) of the reprojections and the à-trous.
    for (const char* name : {"svgf_reproject", "svgf_reproject_pair", "svgf_filter_moments", "svgf_atrous",
                             "svgf_atrous_pair", "svgf_modulate", "two_history_reproject",
                             "two_history_reproject_pair"}) {
        auto code = ShaderCode(name);
        REQUIRE(code.size() > 5);
        CHECK(code[0] == 0x07230203u);  // SPIR-V magic
        CHECK(ShaderCode(std::string(name) + "_fp16").size() > 5);
    }
    CHECK_THROWS_AS(ShaderCode("no_such_shader"), Error);
}

TEST_CASE("unknown device index is a one-line error listing the devices", "[vk][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    VulkanContextOptions o;
    o.device = "99";
    o.validation = Validation::Off;
    try {
        VulkanContext::Create(o);
        FAIL("expected fovrt::Error");
    } catch (const Error& e) {
        std::string what = e.what();
        CHECK(what.find("99") != std::string::npos);
        CHECK(what.find("denoise.device") != std::string::npos);
        CHECK(what.find("devices present: 0:") != std::string::npos);
        CHECK(what.find('\n') == std::string::npos);
    }
    o.device = "banana";
    CHECK_THROWS_AS(VulkanContext::Create(o), Error);
}

TEST_CASE("buffers, dispatch, timestamps and accounting", "[vk][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    VulkanContext ctx = VulkanContext::Create(TestOptions());
    VulkanContext moved = std::move(ctx);  // move-only context stays usable
    VulkanContext& c = moved;
    INFO("device: " << c.deviceName() << ", validation " << c.validationEnabled());
    const int w = 13, h = 7;  // not a multiple of the workgroup
    const size_t n = size_t(w) * h;
    {
        auto& alloc = c.allocator();
        CHECK(alloc.LiveBytes() == 0);
        Buffer illum0 = alloc.CreateBuffer("illum0", 16 * n);
        Buffer illum1 = alloc.CreateBuffer("illum1", 16 * n);
        Buffer albedo = alloc.CreateBuffer("albedo", 12 * n);
        Buffer emission = alloc.CreateBuffer("emission", 12 * n);
        Buffer out = alloc.CreateBuffer("out", 12 * n);
        Buffer staging = alloc.CreateBuffer("staging", 1 << 16, MemoryUsage::Staging);
        CHECK(alloc.LiveBytes() == 16 * n * 2 + 12 * n * 3 + (1 << 16));
        CHECK(alloc.LiveAllocations().size() == 6);
        CHECK(alloc.LiveAllocations()[0].name == "illum0");

        std::vector<vec4> i0(n), i1(n);
        std::vector<vec3> a(n), e(n);
        for (size_t i = 0; i < n; ++i) {
            i0[i] = vec4(float(i), 1.0f, 2.0f, 9.0f);
            i1[i] = vec4(0.5f, float(i % 5), 0.25f, 9.0f);
            a[i] = vec3(0.5f, 2.0f, 1.0f);
            e[i] = vec3(0.0f, 0.0f, float(i));
        }
        ComputePipeline pipe(c, "svgf_modulate", SVGF_MODULATE_BINDINGS, sizeof(ImageSizePush), 2,
                             StageTexelFormats(StageShader::Modulate, false, Precision::Fp32));
        std::array<const Buffer*, SVGF_MODULATE_BINDINGS> b{};
        b[SVGF_MODULATE_B_ILLUM0] = &illum0;
        b[SVGF_MODULATE_B_ILLUM1] = &illum1;
        b[SVGF_MODULATE_B_ALBEDO] = &albedo;
        b[SVGF_MODULATE_B_EMISSION] = &emission;
        b[SVGF_MODULATE_B_OUT] = &out;
        VkDescriptorSet set = pipe.MakeSet(b);
        TimestampPool ts(c, 4);
        CommandRecorder rec(c, &ts);
        size_t off = 0;
        off = rec.Upload(i0.data(), 16 * n, staging, off, illum0);
        off = rec.Upload(i1.data(), 16 * n, staging, off, illum1);
        off = rec.Upload(a.data(), 12 * n, staging, off, albedo);
        off = rec.Upload(e.data(), 12 * n, staging, off, emission);
        rec.Barrier();
        rec.BeginPass("modulate");
        ImageSizePush push{ivec2(w, h)};
        rec.Dispatch(pipe, set, &push, sizeof(push), DispatchGroups(w, h));
        rec.Barrier();
        rec.EndPass();
        rec.Download(out, 12 * n, staging, off);
        rec.Barrier();
        rec.Submit();
        std::vector<vec3> result(n);
        std::memcpy(result.data(), static_cast<char*>(staging.mapped()) + off, 12 * n);
        for (size_t i = 0; i < n; ++i) {
            vec3 expect = a[i] * (vec3(i0[i]) + vec3(i1[i])) + e[i];
            REQUIRE(result[i].x == Approx(expect.x));
            REQUIRE(result[i].y == Approx(expect.y));
            REQUIRE(result[i].z == Approx(expect.z));
        }
        auto times = ts.Results();
        if (c.supportsTimestamps()) {
            REQUIRE(times.size() == 1);
            CHECK(times[0].first == "modulate");
            CHECK(times[0].second >= 0.0);
            CHECK(times[0].second < 10000.0);
        }
    }
    CHECK(c.allocator().LiveBytes() == 0);  // every Buffer freed itself
    CHECK(c.allocator().PeakBytes() > 0);
    CHECK(c.validationErrors() == 0);
}

TEST_CASE("wrapping external handles does not take ownership", "[vk][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    VulkanContext owner = VulkanContext::Create(TestOptions());
    {
        ExternalVulkan ext{owner.instance(), owner.physicalDevice(), owner.device(), owner.queue(),
                           owner.queueFamily(), owner.supports16BitStorage()};
        VulkanContext wrapped = VulkanContext::Wrap(ext);
        CHECK(wrapped.device() == owner.device());
        Buffer b = wrapped.allocator().CreateBuffer("x", 64);
        CommandRecorder rec(wrapped);
        rec.Fill(b, 7u);
        rec.Submit();
    }  // wrapped destroyed: the owner's device must still work
    Buffer b = owner.allocator().CreateBuffer("y", 64);
    Buffer s = owner.allocator().CreateBuffer("s", 64, MemoryUsage::Staging);
    CommandRecorder rec(owner);
    rec.Fill(b, 0x01020304u);
    rec.Barrier();
    rec.Download(b, 64, s, 0);
    rec.Barrier();
    rec.Submit();
    uint32_t v;
    std::memcpy(&v, s.mapped(), 4);
    CHECK(v == 0x01020304u);
    CHECK(owner.validationErrors() == 0);
    CHECK_THROWS_AS(VulkanContext::Wrap(ExternalVulkan{}), Error);
}

TEST_CASE("the debug messenger counts validation errors", "[vk][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    VulkanContext c = VulkanContext::Create(TestOptions());
    if (!c.validationEnabled()) FOVRT_SKIP("VK_LAYER_KHRONOS_validation not installed");
    // Deliberate misuse: a zero-sized buffer (VUID-VkBufferCreateInfo-size-00912).
    auto info = VkInit<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = 0;
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    std::fprintf(stderr, "(the next validation error is expected)\n");
    if (vkCreateBuffer(c.device(), &info, nullptr, &buffer) == VK_SUCCESS && buffer != VK_NULL_HANDLE)
        vkDestroyBuffer(c.device(), buffer, nullptr);
    CHECK(c.validationErrors() >= 1);
}

// The transfer ring (vk/transfer_ring.h): transfers larger than the ring arrive whole, in order,
// through as many submits as they need; a pass spanning the flushes keeps its timestamps; what
// fits is one submit.
TEST_CASE("the transfer ring streams uploads and downloads larger than itself", "[vk][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    VulkanContext c = VulkanContext::Create(TestOptions());
    std::vector<uint8_t> first(1000), second(300);
    for (size_t i = 0; i < first.size(); ++i) first[i] = uint8_t(i * 7 + 3);
    for (size_t i = 0; i < second.size(); ++i) second[i] = uint8_t(255 - i);
    Buffer a = c.allocator().CreateBuffer("a", first.size());
    Buffer b = c.allocator().CreateBuffer("b", second.size());
    Buffer copy = c.allocator().CreateBuffer("copy", first.size());
    for (const size_t ringBytes : {size_t(40), size_t(4096)}) {
        INFO("ring " << ringBytes << " bytes");
        Buffer ring = c.allocator().CreateBuffer("ring", ringBytes, MemoryUsage::Staging);
        TimestampPool ts(c, 1);
        CommandRecorder rec(c, &ts);
        TransferRing transfers(rec, ring);
        rec.BeginPass("frame");
        transfers.Upload(first.data(), first.size(), a);
        transfers.Upload(second.data(), second.size(), b);
        rec.Barrier();
        rec.Copy(a, copy, first.size());  // device work between the uploads and the downloads
        rec.Barrier();
        rec.EndPass();
        std::vector<uint8_t> gotCopy(first.size()), gotB(second.size());
        transfers.Download(copy, gotCopy.size(), gotCopy.data());
        transfers.Download(b, gotB.size(), gotB.data());
        transfers.Submit();
        CHECK(gotCopy == first);
        CHECK(gotB == second);
        // 2,600 bytes of transfers through 40: a flush every 40 bytes or fewer (the ring's room
        // after 16-byte alignment); through 4,096: none.
        if (ringBytes == 40) CHECK(transfers.flushes() >= 2600 / 40);
        else CHECK(transfers.flushes() == 0);
        if (ts.enabled()) {
            const auto passes = ts.Results();
            REQUIRE(passes.size() == 1);
            CHECK(passes[0].first == "frame");
            CHECK(passes[0].second >= 0.0);
        }
    }
    CHECK(c.validationErrors() == 0);
}
