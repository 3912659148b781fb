// DenoiserBuffers: the GPU buffers of one plan-driven Vulkan denoiser, one per allocation of its
// memory plan (so `fovrt memory` lists exactly what exists), its planes addressed by typed
// BufferKey (denoise/planes.h), several transient planes in one slot of the transient pool;
// clearing them on a reset; synchronous read-backs for tests and debug views. The allocations the
// plan marks shared (the transient pool's slots, the staging ring) are the device's
// SharedBuffers, which every denoiser on it uses in turn, one frame at a time.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "denoise/denoiser.h"
#include "denoise/pass_plan.h"
#include "vk/allocator.h"
#include "vk/context.h"
#include "vk/recorder.h"
#include "vk/shared_buffers.h"

namespace fovrt {

class DenoiserBuffers {
public:
    // `owner` names the denoiser in error messages.
    explicit DenoiserBuffers(std::string owner = "vulkan denoiser") : owner_(std::move(owner)) {}

    // Replaces every buffer by the plan's allocations (plan.buffers) and places its planes
    // (plan.planes) in them; staging planes are host-visible; shared allocations are reserved
    // in the device's SharedBuffers.
    void Allocate(VulkanContext& context, const DenoiserPlan& plan);
    // Called before a frame is recorded: the shared buffers hold this denoiser's planes from
    // now on (a read-back of a shared plane after another user's frame fails).
    void BeginFrame() { shared_->Claim(user_); }
    // Advances when a shared buffer was replaced: descriptor sets made before are stale.
    uint64_t SharedGeneration() const { return shared_ ? shared_->generation() : 0; }
    // The buffer that holds a plane (a pool slot may be larger than the plane: see Bytes).
    Buffer& operator[](const BufferKey& key);
    size_t Bytes(const BufferKey& key) const;  // the plane's own size
    void Release() {  // e.g. before descriptor layouts change
        planes_.clear();
        allocations_.clear();
        sharedNames_.clear();
        shared_.reset();  // the last user's release frees the shared buffers
    }

    // Drops every history: each device buffer to its plane's ClearValue (background object ids,
    // so nothing reprojects; 0 elsewhere).
    void RecordClear(CommandRecorder& rec, Precision precision);  // ClearValue at that precision

    // Synchronous read-back of one buffer, by key or by its printed name (tests), after a frame:
    // fails for a transient plane whose slot a later plane of the frame reused, or once another
    // denoiser on the device has run a frame with the shared buffers.
    std::vector<uint8_t> Read(VulkanContext& context, const BufferKey& key);
    std::vector<uint8_t> Read(VulkanContext& context, const std::string& name);
    bool Readable(const std::string& name) const;  // a plane of the plan that Read() accepts
    // The same as floats, stored with `scalarBytes` per scalar: 2 for fp16 history storage, 4
    // otherwise (ScalarBytes of the plane at the plan's precision).
    std::vector<float> ReadFloats(VulkanContext& context, const BufferKey& key, size_t scalarBytes);
    // A one-scalar-per-pixel buffer as a W×H plane (debug views); checks the buffer's size.
    void ReadPlane(VulkanContext& context, const BufferKey& key, int width, int height,
                   size_t scalarBytes, Plane<float>& out);

private:
    struct Placement {
        size_t allocation = 0;
        size_t bytes = 0;
        bool heldAfterFrame = true;  // no plane written later shares its slot (HeldAfterFrame)
    };
    const Placement& Find(const BufferKey& key) const;
    Buffer& Allocation(size_t allocation);
    bool Shared(size_t allocation) const { return !sharedNames_[allocation].empty(); }
    std::vector<uint8_t> Read(VulkanContext& context, Buffer& src, size_t bytes);
    std::string owner_;
    std::vector<Buffer> allocations_;        // by plan.buffers index; empty where shared
    std::vector<std::string> sharedNames_;   // by plan.buffers index; "" where the buffer is own
    std::shared_ptr<SharedBuffers> shared_;
    uint64_t user_ = 0;
    std::map<BufferKey, Placement> planes_;
};

// Per-pass GPU timings of the last submitted frame.
std::vector<PassTiming> PassTimings(const TimestampPool& timestamps);

}  // namespace fovrt
