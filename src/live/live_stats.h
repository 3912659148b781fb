// LiveStats: what a live session measures per shown frame, kept as a short rolling history for
// the panel's plots and as running sums for the end-of-session summary (nothing grows with the
// session's length). Per-frame records go to an optional JSON Lines stream as they happen.
#pragma once

#include <cstdint>
#include <cstdio>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "live/live_loop.h"

namespace fovrt {

struct ShownFrameStats {
    uint64_t number = 0;
    double latencyMs = 0.0;  // gaze sample taken -> vkQueuePresentKHR returned for this frame
    double presentMs = 0.0;  // the window's compose + ImGui + submit + present
    LiveTimings timings;     // the render thread's
};

class LiveStats {
public:
    static constexpr size_t kHistory = 240;  // frames kept for plots

    // `streamPath` empty: no per-frame stream. The stream is line-buffered JSON, one object per
    // shown frame, so a session closed at any moment leaves whole lines.
    explicit LiveStats(const std::string& streamPath = "");
    ~LiveStats();
    LiveStats(const LiveStats&) = delete;
    LiveStats& operator=(const LiveStats&) = delete;

    void Add(const ShownFrameStats& frame);
    void AddDisplayFrame(double presentMs);  // every window present, new frame or not

    const std::deque<ShownFrameStats>& History() const { return history_; }
    uint64_t Frames() const { return frames_; }
    // Rendered frames per second over the history window.
    double FramesPerSecond() const;
    double DisplayFramesPerSecond() const;
    // Median / 95th percentile of the history's latency.
    double LatencyPercentile(double q) const;
    // "60 frames in 5.8 s: 10.3 frames/s; gaze-to-photon latency median 95 ms, p95 120 ms; ..."
    // (frames shown: a frame rendered faster than the window presents may never be shown)
    std::string Summary() const;
    // The same figures for a manifest: frames, seconds, frames_per_s, latency_ms {median, p95},
    // mean_ms {trace, denoise, present}, mrays_per_s.
    nlohmann::json SummaryJson() const;

private:
    std::FILE* stream_ = nullptr;
    std::deque<ShownFrameStats> history_;
    std::deque<LiveClock::time_point> shownAt_;
    std::deque<LiveClock::time_point> displayAt_;
    LiveClock::time_point start_ = LiveClock::now();
    uint64_t frames_ = 0;
    uint64_t displayFrames_ = 0;
    double sumTrace_ = 0, sumDenoise_ = 0, sumPresent_ = 0, sumLatency_ = 0, sumFrame_ = 0;
    uint64_t sumRays_ = 0;
    std::vector<double> allLatencies_;  // bounded: a reservoir of kReservoir samples
    static constexpr size_t kReservoir = 4096;
    std::minstd_rand rng_{1};
};

}  // namespace fovrt
