#include "vk/bandwidth.h"

#include <algorithm>
#include <array>
#include <chrono>

#include "shaders/push_constants.h"
#include "shaders/shared_constants.h"
#include "vk/allocator.h"
#include "vk/context.h"
#include "vk/pipeline.h"
#include "vk/recorder.h"

namespace fovrt {

namespace {

constexpr uint32_t kRowElements = 4096;  // vec4 elements per dispatch row

}  // namespace

DeviceBandwidth MeasureDeviceBandwidth(VulkanContext& context, size_t megabytes, int runs) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(context.physicalDevice(), &props);
    size_t elements = (megabytes << 20) / 16;
    elements = std::min<size_t>(elements, props.limits.maxTexelBufferElements);
    const uint32_t rows = uint32_t(std::max<size_t>(1, elements / kRowElements));
    const uint32_t columns = uint32_t(std::min<size_t>(elements, kRowElements));
    DeviceBandwidth result;
    result.bytes = size_t(rows) * columns * 16;

    Buffer src = context.allocator().CreateBuffer("bandwidth.src", result.bytes);
    Buffer dst = context.allocator().CreateBuffer("bandwidth.dst", result.bytes);
    const std::array<VkFormat, BANDWIDTH_BINDINGS> formats{VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_UNDEFINED,
                                                           VK_FORMAT_UNDEFINED};
    TimestampPool timestamps(context, 1);
    CommandSlot slot(context);
    {
        CommandRecorder rec(context, slot);
        rec.Fill(src, 0x3F800000u);  // 1.0f: finite data
        rec.Barrier();
        rec.Submit();
    }
    const uvec2 groups((columns + FOVRT_WORKGROUP_X - 1) / FOVRT_WORKGROUP_X, rows);
    const std::array<const Buffer*, BANDWIDTH_BINDINGS> bindings{&src, &src, &dst};
    double seconds[3] = {};
    for (int32_t mode : {0, 1, 2}) {  // the shader's specialization constant kMode
        ComputePipeline copy(context, "bandwidth_copy", BANDWIDTH_BINDINGS, sizeof(BandwidthPush), 1, formats,
                             std::span<const int32_t>(&mode, 1));
        VkDescriptorSet set = copy.MakeSet(bindings);
        double best = 1e30;
        for (int run = 0; run <= std::max(runs, 1); ++run) {  // run 0: warm-up
            CommandRecorder rec(context, slot, &timestamps);
            const BandwidthPush push{ivec2(int(columns), int(rows))};
            rec.BeginPass("copy");
            rec.Dispatch(copy, set, &push, sizeof(push), groups);
            rec.EndPass();
            const auto t0 = std::chrono::steady_clock::now();
            rec.Submit();
            double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            if (timestamps.enabled()) seconds = timestamps.Results().at(0).second * 1e-3;
            if (run > 0) best = std::min(best, seconds);
        }
        seconds[mode] = best;
    }
    result.texelGBps = 2.0 * double(result.bytes) / seconds[0] / 1e9;
    result.storageGBps = 2.0 * double(result.bytes) / seconds[1] / 1e9;
    // Elements × exp2 per element over the time beyond the plain copy; 0 when the difference is
    // lost in the noise (a GPU hides the exp2 behind the memory traffic).
    const double exp2Count = double(result.bytes / 16) * BANDWIDTH_EXP2_PER_ELEMENT;
    if (seconds[2] > 1.1 * seconds[0]) result.exp2PerSecond = exp2Count / (seconds[2] - seconds[0]);
    return result;
}

}  // namespace fovrt
