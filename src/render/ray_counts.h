// The tracer's work counters: RayCounts per tile (no atomics on the hot path), summed into a
// renderer's RenderCounters once per tile (RenderStats, renderer.h).
#pragma once

#include <atomic>
#include <cstdint>

#include "render/renderer.h"

namespace fovrt {

struct RayCounts {
    uint64_t primary = 0, guide = 0, shadow = 0, shadowReused = 0, bounce = 0, samples = 0, dropped = 0;
};

class RenderCounters {
public:
    void Add(const RayCounts& c) {
        primaryRays_ += c.primary;
        guideRays_ += c.guide;
        shadowRays_ += c.shadow;
        shadowRaysReused_ += c.shadowReused;
        bounceRays_ += c.bounce;
        samples_ += c.samples;
        dropped_ += c.dropped;
    }
    RenderStats Stats() const {
        RenderStats s;
        s.primaryRays = primaryRays_.load();
        s.guideRays = guideRays_.load();
        s.shadowRays = shadowRays_.load();
        s.shadowRaysReused = shadowRaysReused_.load();
        s.bounceRays = bounceRays_.load();
        s.samples = samples_.load();
        s.droppedSamples = dropped_.load();
        return s;
    }
    void Reset() {
        primaryRays_ = 0;
        guideRays_ = 0;
        shadowRays_ = 0;
        shadowRaysReused_ = 0;
        bounceRays_ = 0;
        samples_ = 0;
        dropped_ = 0;
    }

private:
    std::atomic<uint64_t> primaryRays_{0}, guideRays_{0}, shadowRays_{0}, shadowRaysReused_{0}, bounceRays_{0}, samples_{0},
        dropped_{0};
};

}  // namespace fovrt
