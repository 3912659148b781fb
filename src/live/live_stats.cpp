#include "live/live_stats.h"

#include <algorithm>
#include <random>

#include <fmt/format.h>

#include "core/error.h"

namespace fovrt {
namespace {

double Percentile(std::vector<double> values, double q) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const double at = q * double(values.size() - 1);
    const size_t i = size_t(at);
    const double t = at - double(i);
    return i + 1 < values.size() ? values[i] * (1.0 - t) + values[i + 1] * t : values[i];
}

double SecondsBetween(LiveClock::time_point a, LiveClock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

}  // namespace

LiveStats::LiveStats(const std::string& streamPath) {
    if (streamPath.empty()) return;
    stream_ = std::fopen(streamPath.c_str(), "w");
    if (!stream_) Fail("{}: cannot open the per-frame stats file for writing", streamPath);
    std::setvbuf(stream_, nullptr, _IOLBF, 1 << 16);
}

LiveStats::~LiveStats() {
    if (stream_) std::fclose(stream_);
}

void LiveStats::Add(const ShownFrameStats& f) {
    const auto now = LiveClock::now();
    history_.push_back(f);
    shownAt_.push_back(now);
    if (history_.size() > kHistory) {
        history_.pop_front();
        shownAt_.pop_front();
    }
    ++frames_;
    sumTrace_ += f.timings.traceMs + f.timings.sppMs;
    sumDenoise_ += f.timings.denoiseMs;
    sumPresent_ += f.presentMs;
    sumLatency_ += f.latencyMs;
    sumFrame_ += f.timings.frameMs;
    sumRays_ += f.timings.rays;
    // Reservoir sampling keeps the whole-session percentile honest in bounded memory.
    if (allLatencies_.size() < kReservoir) {
        allLatencies_.push_back(f.latencyMs);
    } else {
        const uint64_t slot = std::uniform_int_distribution<uint64_t>(0, frames_ - 1)(rng_);
        if (slot < kReservoir) allLatencies_[slot] = f.latencyMs;
    }
    if (stream_) {
        std::string passes;
        for (const PassTiming& p : f.timings.passes)
            passes += fmt::format("{}\"{}\":{:.4f}", passes.empty() ? "" : ",", p.pass, p.ms);
        fmt::print(stream_,
                   "{{\"frame\":{},\"shown_s\":{:.4f},\"latency_ms\":{:.3f},\"present_ms\":{:.3f},\"spp_ms\":{:.3f},"
                   "\"trace_ms\":{:.3f},\"denoise_ms\":{:.3f},\"view_ms\":{:.3f},\"frame_ms\":{:.3f},"
                   "\"rays\":{},\"guide_rays\":{},\"passes_ms\":{{{}}}}}\n",
                   f.number, SecondsBetween(start_, now), f.latencyMs, f.presentMs, f.timings.sppMs, f.timings.traceMs,
                   f.timings.denoiseMs, f.timings.viewMs, f.timings.frameMs, f.timings.rays, f.timings.guideRays,
                   passes);
    }
}

void LiveStats::AddDisplayFrame(double) {
    displayAt_.push_back(LiveClock::now());
    if (displayAt_.size() > kHistory) displayAt_.pop_front();
    ++displayFrames_;
}

double LiveStats::FramesPerSecond() const {
    if (shownAt_.size() < 2) return 0.0;
    return double(shownAt_.size() - 1) / std::max(1e-9, SecondsBetween(shownAt_.front(), shownAt_.back()));
}

double LiveStats::DisplayFramesPerSecond() const {
    if (displayAt_.size() < 2) return 0.0;
    return double(displayAt_.size() - 1) /
           std::max(1e-9, SecondsBetween(displayAt_.front(), displayAt_.back()));
}

double LiveStats::LatencyPercentile(double q) const {
    std::vector<double> values;
    for (const auto& f : history_) values.push_back(f.latencyMs);
    return Percentile(values, q);
}

std::string LiveStats::Summary() const {
    if (frames_ == 0) return "no frame was shown";
    const double seconds = SecondsBetween(start_, LiveClock::now());
    const double n = double(frames_);
    return fmt::format(
        "{} frames in {:.1f} s: {:.2f} frames/s (last {}: {:.2f}); gaze-to-photon latency median "
        "{:.1f} ms, p95 {:.1f} ms; per frame: trace {:.1f} ms, denoise {:.1f} ms, present {:.1f} ms; "
        "{:.2f} Mrays/s while tracing; {} window presents",
        frames_, seconds, n / seconds, history_.size(), FramesPerSecond(),
        Percentile(allLatencies_, 0.5), Percentile(allLatencies_, 0.95), sumTrace_ / n, sumDenoise_ / n,
        sumPresent_ / n, sumTrace_ > 0 ? double(sumRays_) / (sumTrace_ * 1e-3) * 1e-6 : 0.0, displayFrames_);
}

nlohmann::json LiveStats::SummaryJson() const {
    const double n = std::max(1.0, double(frames_));
    const double seconds = SecondsBetween(start_, LiveClock::now());
    return {{"frames", frames_},
            {"seconds", seconds},
            {"frames_per_s", frames_ ? double(frames_) / seconds : 0.0},
            {"latency_ms", {{"median", Percentile(allLatencies_, 0.5)}, {"p95", Percentile(allLatencies_, 0.95)}}},
            {"mean_ms", {{"trace", sumTrace_ / n}, {"denoise", sumDenoise_ / n}, {"present", sumPresent_ / n}}},
            {"mrays_per_s", sumTrace_ > 0 ? double(sumRays_) / (sumTrace_ * 1e-3) * 1e-6 : 0.0}};
}

}  // namespace fovrt
