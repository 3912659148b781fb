#include "metrics/vdp_stream.h"

#include <algorithm>

#include "metrics/vdp_temporal.h"

namespace fovrt {

VdpStream::VdpStream(VdpGeometry geometry, double fps)
    : vdp_(geometry), fps_(fps), window_(size_t(std::max(2, VdpTemporalFilterLength(fps)))) {}

void VdpStream::Reset() {
    test_.clear();
    reference_.clear();
    fixations_.clear();
}

Plane<float> VdpStream::Next(Plane<float> test, Plane<float> reference, VdpFixation fixation) {
    if (!test_.empty() && (test_.back().width() != test.width() || test_.back().height() != test.height())) Reset();
    if (test_.empty()) {
        // The first frame fills the window: Score's padding before a sequence's first frame.
        test_.assign(window_ - 1, test);
        reference_.assign(window_ - 1, reference);
        fixations_.assign(window_ - 1, fixation);
    } else {
        test_.erase(test_.begin());
        reference_.erase(reference_.begin());
        fixations_.erase(fixations_.begin());
    }
    test_.push_back(std::move(test));
    reference_.push_back(std::move(reference));
    fixations_.push_back(fixation);
    VdpOptions options;
    options.foveated = true;
    options.fixations = fixations_;
    options.diffMaps = true;
    options.firstScoredFrame = int(window_) - 1;
    return std::move(vdp_.Score(test_, reference_, fps_, options).diffMaps.front());
}

}  // namespace fovrt
