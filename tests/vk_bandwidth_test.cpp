// Device streaming bandwidth (vk/bandwidth.h) and the reusable command slot of the recorder.
#include <cmath>
#include <cstring>
#include <string>

#include "test_support.h"
#include "vk/bandwidth.h"
#include "vk/context.h"
#include "vk/recorder.h"
#include "vk_test_support.h"

using namespace fovrt;

TEST_CASE("device streaming-copy bandwidth is positive and finite", "[vk][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    VulkanContext& c = *test::TestContext();
    const DeviceBandwidth bw = MeasureDeviceBandwidth(c, 4, 1);
    CHECK(bw.bytes == (size_t(4) << 20));
    CHECK(std::isfinite(bw.texelGBps));
    CHECK(std::isfinite(bw.storageGBps));
    CHECK(bw.texelGBps > 0.0);
    CHECK(bw.storageGBps > 0.0);
    // 0 when the exp2 cost is lost in timing noise (a GPU hides it; a loaded CPU blurs it).
    CHECK(std::isfinite(bw.exp2PerSecond));
    CHECK(bw.exp2PerSecond >= 0.0);
    CHECK(c.allocator().LiveBytes() == 0);
    CHECK(c.validationErrors() == 0);
}

TEST_CASE("one command slot serves many recorders", "[vk][vulkan]") {
    if (!VulkanContext::Available()) FOVRT_SKIP("no Vulkan device");
    VulkanContext& c = *test::TestContext();
    Buffer b = c.allocator().CreateBuffer("slot.b", 64);
    Buffer s = c.allocator().CreateBuffer("slot.s", 64, MemoryUsage::Staging);
    CommandSlot slot(c);
    for (uint32_t frame = 0; frame < 4; ++frame) {
        {
            CommandRecorder abandoned(c, slot);  // recorded, never submitted: dropped
            abandoned.Fill(b, 0xDEADBEEFu);
        }
        CommandRecorder rec(c, slot);
        rec.Fill(b, frame + 1);
        rec.Barrier();
        rec.Download(b, 64, s, 0);
        rec.Barrier();
        rec.Submit();
        uint32_t v = 0;
        std::memcpy(&v, s.mapped(), 4);
        CHECK(v == frame + 1);
    }
    CHECK(c.validationErrors() == 0);
}
