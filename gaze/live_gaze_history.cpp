#include "gaze/live_gaze_history.h"

#include <algorithm>

namespace fovrt {

namespace {

// The first sample taken after t.
std::deque<GazeSample>::const_iterator FirstAfter(const std::deque<GazeSample>& samples, double t) {
    return std::upper_bound(samples.begin(), samples.end(), t,
                            [](double time, const GazeSample& s) { return time < s.timeSeconds; });
}

}  // namespace

GazeSample LiveGazeHistory::At(double t) const {
    if (samples_.empty()) return GazeSample{t, vec3(0, 0, -1), false};
    const auto after = FirstAfter(samples_, t);
    return after == samples_.begin() ? samples_.front() : *(after - 1);
}

bool LiveGazeHistory::Add(const GazeSample& sample) {
    if (!samples_.empty()) {
        const double newest = samples_.back().timeSeconds;
        if (sample.timeSeconds < newest) return false;
        if (sample.timeSeconds == newest) {
            samples_.back() = sample;
            return true;
        }
    }
    samples_.push_back(sample);
    return true;
}

void LiveGazeHistory::DropBefore(double oldest) {
    const auto after = FirstAfter(samples_, oldest);
    if (after == samples_.begin()) return;
    samples_.erase(samples_.begin(), after - 1);  // keep the one At(oldest) returns
}

}  // namespace fovrt
