// Streaming bandwidth of the Vulkan device, measured with shaders/bandwidth_copy.comp through the
// same access layer the denoiser passes use, timed with GPU timestamps: the device-side bandwidth
// bound of `fovrt bench --denoisers` (next to the host memcpy figure). On a discrete GPU both
// bounds describe device DRAM; on lavapipe the compute copy is far slower than memcpy. The same
// shader also measures the device's exp2 throughput (one exp2 per edge-stopping weight and
// channel is the floor of an à-trous tap), to tell bandwidth-bound from ALU-bound passes.
#pragma once

#include <cstddef>

namespace fovrt {

class VulkanContext;

struct DeviceBandwidth {
    double texelGBps = 0.0;    // rgba32f uniform texel buffer read → std430 vec4 write
    double storageGBps = 0.0;  // std430 vec4 read → std430 vec4 write
    double exp2PerSecond = 0.0;  // exp2 per second: 64 per element beyond the texel copy (0: not resolved)
    size_t bytes = 0;          // size of the copied buffer (the source; as much is written)
};

// Copies a `megabytes` buffer (clamped to the device's texel-buffer limit) `runs` times per mode
// after one warm-up; keeps the fastest run. GB/s = (bytes read + bytes written) / s / 1e9.
DeviceBandwidth MeasureDeviceBandwidth(VulkanContext& context, size_t megabytes = 256, int runs = 5);

}  // namespace fovrt
