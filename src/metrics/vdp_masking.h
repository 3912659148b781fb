// Masking and pooling of FovVideoVDP 1.2.
//   Masking (per pixel, per band, per channel): with T, R the test and reference contrasts divided
//   by the contrast threshold N = 1/S, the mutual masking signal M = 10^mask_c · min(|T|, |R|) and
//   D = min(|T − R|^p / (1 + M^q), 10⁴).
//   Pooling: per band and channel, the spatial power mean (mean D^β)^{1/β}; the transient channel
//   weighted by w_transient; bands summed (β_sch = 1), channels by a β_tch-norm, frames by a
//   β_t power mean; JOD = 10 + sign(a)·(|a|^{1/b}·Q)^b.
#pragma once

#include <cmath>

#include "metrics/vdp_params.h"

namespace fovrt {

inline float VdpMaskedDifference(float test, float reference, float threshold, float p, float q,
                                 float maskGain) {
    const float t = test / threshold, r = reference / threshold;
    const float m = maskGain * std::min(std::abs(t), std::abs(r));
    const float d = std::pow(std::abs(t - r), p) / (1.0f + std::pow(m, q));
    return std::min(d, 1e4f);
}

// Q → JOD.
inline double VdpJod(double q, const VdpParams& params) {
    const double b = std::pow(10.0, params.logJodExp);
    const double a = std::abs(params.jodA);
    return 10.0 + (params.jodA < 0 ? -1.0 : 1.0) * std::pow(std::pow(a, 1.0 / b) * q, b);
}

}  // namespace fovrt
