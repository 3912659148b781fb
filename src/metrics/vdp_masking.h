// Masking and pooling of FovVideoVDP 1.2.
//   Masking (per pixel, per band, per channel): with T, R the test and reference contrasts divided
//   by the contrast threshold N = 1/S, the mutual masking signal M = 10^mask_c · min(|T|, |R|) and
//   D = min(|T − R|^p / (1 + M^q), 10⁴).
//   Pooling: per band and channel, the spatial power mean (mean D^β)^{1/β}; the transient channel
//   weighted by w_transient; bands summed (β_sch = 1), channels by a β_tch-norm, frames by a
//   β_t power mean; JOD = 10 + sign(a)·(|a|^{1/b}·Q)^b.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "metrics/vdp_fastmath.h"
#include "metrics/vdp_params.h"

namespace fovrt {

inline float VdpMaskedDifference(float test, float reference, float threshold, float p, float q,
                                 float maskGain) {
    const float t = test / threshold, r = reference / threshold;
    const float m = maskGain * std::min(std::abs(t), std::abs(r));
    const float d = std::pow(std::abs(t - r), p) / (1.0f + std::pow(m, q));
    return std::min(d, 1e4f);
}

// log2 of VdpMaskedDifference with the sensitivity S = 1/threshold (−∞ where T = R): the form
// the pooling uses, as powers through exp2/log2 (the metric's hot loop; equal to the above to
// float rounding).
inline float VdpLog2MaskedDifference(float test, float reference, float sensitivity, float p, float q,
                                     float log2MaskGain) {
    const float t = std::abs(test * sensitivity), r = std::abs(reference * sensitivity);
    const float diff = std::abs(test - reference) * sensitivity;
    const float log2Mask = log2MaskGain + std::log2(std::min(t, r));
    const float log2D = p * std::log2(diff) - std::log2(1.0f + std::exp2(q * log2Mask));
    return std::min(log2D, 13.287712f);  // log2(1e4): the reference's clamp
}

// VdpLog2MaskedDifference over a row of pixels, as the metric runs it: log2 S per pixel (the CSF
// table's own form, sensitivity correction included) and VdpFastLog2/VdpFastExp2, so the loop
// vectorises (always inlined: compiled for its caller's target). log2(1 + 2^y) is taken as
// max(y, 0) + log2(1 + 2^−|y|), which cannot overflow.
[[gnu::always_inline]]
inline void VdpLog2MaskedDifferenceRow(const float* test, const float* reference, const float* log2Sensitivity,
                                       std::size_t n, float p, float q, float log2MaskGain, float* log2D) {
    for (std::size_t i = 0; i < n; ++i) {
        const float t = test[i], r = reference[i], log2S = log2Sensitivity[i];
        const float log2Mask = log2MaskGain + log2S + VdpFastLog2(std::min(std::abs(t), std::abs(r)));
        const float y = q * log2Mask;
        const float log2OnePlusMask = std::max(y, 0.0f) + VdpFastLog2(1.0f + VdpFastExp2(-std::abs(y)));
        const float d = p * (VdpFastLog2(std::abs(t - r)) + log2S) - log2OnePlusMask;
        log2D[i] = std::min(d, 13.287712f);  // log2(1e4): the reference's clamp
    }
}

// Q → JOD.
inline double VdpJod(double q, const VdpParams& params) {
    const double b = std::pow(10.0, params.logJodExp);
    const double a = std::abs(params.jodA);
    return 10.0 + (params.jodA < 0 ? -1.0 : 1.0) * std::pow(std::pow(a, 1.0 / b) * q, b);
}

}  // namespace fovrt
