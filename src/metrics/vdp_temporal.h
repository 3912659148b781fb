// Temporal channels of FovVideoVDP: the sustained channel filters luminance over time with a
// log-Gaussian impulse response exp(−(ln(t + 10⁻⁴) − ln β)² / 2σ²) (normalised to sum 1); the
// transient channel with its finite difference scaled by 0.0622/Δt. Filters span 250 ms:
// ⌈250 / (1000/fps)⌉ taps, sampled like the reference at t = linspace(0, taps/fps, taps) (so the
// sample spacing is slightly above 1/fps: a reading kept for agreement with it). Tap 0 weights the
// current frame, tap k the frame k frames earlier (the first frame repeats before the start).
#pragma once

#include <vector>

#include "core/image.h"
#include "metrics/vdp_params.h"

namespace fovrt {

struct VdpTemporalFilters {
    std::vector<float> sustained;
    std::vector<float> transient;
};

int VdpTemporalFilterLength(double fps);
VdpTemporalFilters MakeVdpTemporalFilters(double fps, const VdpParams& params);
// Frame `frame` of `frames` filtered by `taps` (tap k weights the frame k earlier; frame 0
// repeats before the start, the reference's "replicate" padding).
Plane<float> VdpFilterFrame(const std::vector<Plane<float>>& frames, int frame, const std::vector<float>& taps);
// Both channels of frame `frame` in one pass over the frames the filters reach (the metric's
// form: each frame read once for both); equal to VdpFilterFrame with each filter's taps.
void VdpFilterFrameChannels(const std::vector<Plane<float>>& frames, int frame, const VdpTemporalFilters& filters,
                            Plane<float>& sustained, Plane<float>& transient);

}  // namespace fovrt
