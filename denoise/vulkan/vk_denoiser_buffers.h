// DenoiserBuffers: the named GPU buffers of one Vulkan denoiser, allocated by iterating its memory
// plan (so `fovrt memory` lists exactly what exists), and the per-frame steps every Vulkan
// denoiser shares: clearing histories on Reset(), uploading the FrameInputs planes all SVGF-family
// passes read, downloading the output and the sanitising counters, reading a buffer back (tests
// and debug views).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/frame_inputs.h"
#include "denoise/denoiser.h"
#include "vk/allocator.h"
#include "vk/context.h"
#include "vk/recorder.h"

namespace fovrt {

class DenoiserBuffers {
public:
    // `owner` names the denoiser in error messages.
    explicit DenoiserBuffers(std::string owner = "vulkan denoiser") : owner_(std::move(owner)) {}

    // Replaces every buffer by the plan's; names starting with "staging" are host-visible.
    void Allocate(VulkanContext& context, const std::vector<BufferPlan>& plan);
    // fovrt::Error naming the owner when the plan has no such buffer.
    Buffer& operator[](const std::string& name);
    void Release() { buffers_.clear(); }  // e.g. before descriptor layouts change

    // Drops every history: object ids ~0 (background, so nothing reprojects), all else 0.
    void RecordClear(CommandRecorder& rec);
    // Uploads every FrameInputs plane (its plane list) but the sample counts into input.* and
    // geometry.*.<side>, through "staging" from offset 0, and zeroes the counters. Returns the
    // next free staging offset.
    size_t RecordUploadInputs(CommandRecorder& rec, const FrameInputs& in, const std::string& side);

    // Records the download of "output" and "stats" to "staging" at `stagingOffset`; after
    // Submit(), FinishOutput() copies them into `output` and adds the counters to `stats`.
    void RecordDownloadOutput(CommandRecorder& rec, size_t stagingOffset, size_t pixels);
    void FinishOutput(int width, int height, Plane<vec3>& output, DenoiseStats& stats);

    // Synchronous read-back of one buffer (tests: history contents after Denoise()).
    std::vector<uint8_t> Read(VulkanContext& context, const std::string& name);
    // The same as floats, stored with `scalarBytes` per scalar: 2 for fp16 history storage, 4
    // otherwise (HistoryScalarBytes of the plan's precision for history planes).
    std::vector<float> ReadFloats(VulkanContext& context, const std::string& name,
                                  size_t scalarBytes);
    // A one-scalar-per-pixel buffer as a W×H plane (debug views); checks the buffer's size.
    void ReadPlane(VulkanContext& context, const std::string& name, int width, int height,
                   size_t scalarBytes, Plane<float>& out);

private:
    std::string owner_;
    std::map<std::string, Buffer> buffers_;
    size_t outputOffset_ = 0, statsOffset_ = 0;
};

// Per-pass GPU timings of the last submitted frame.
std::vector<PassTiming> PassTimings(const TimestampPool& timestamps);

}  // namespace fovrt
