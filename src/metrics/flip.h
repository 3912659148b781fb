// LDR-FLIP (Andersson et al. 2020, "FLIP: A Difference Evaluator for Alternating Images"),
// implemented from the paper with the constants of NVIDIA's published reference implementation:
//   opponent space YyCxCz (linear: Yy = 116 Y/Yn − 16, Cx = 500 (X/Xn − Y/Yn), Cz = 200 (Y/Yn − Z/Zn)),
//   CSF filters as sums of Gaussians in degrees — achromatic (a1 1, b1 0.0047), red-green
//   (a1 1, b1 0.0053), blue-yellow (a1 34.1, b1 0.04, a2 13.5, b2 0.025) — radius
//   ceil(3 sqrt(b_max / 2π²) ppd), each normalised to sum 1, replicate borders; back to linear RGB,
//   clamp to [0,1], CIELAB with Hunt adjustment (a,b ×= 0.01 L), HyAB distance^qc (qc = 0.7),
//   redistributed with pc = 0.4, pt = 0.95 against cmax = HyAB(green, blue)^qc;
//   features on normalised Y: edge (first derivative) and point (second derivative) of a Gaussian
//   with σ = ½·0.082·ppd, radius ceil(3σ), positive/negative weights normalised to ±1;
//   ΔE_f = (max(|‖edge_r‖ − ‖edge_t‖|, |‖point_r‖ − ‖point_t‖|) / √2)^qf, qf = 0.5;
//   FLIP = ΔE_c^(1 − ΔE_f), in [0, 1].
// All kernels are separable (the sign split of the feature kernels depends on one axis only), so
// the 2D filters run as 1D passes; the result equals the 2D reference kernels.
#pragma once

#include <cstdint>

#include "core/camera.h"
#include "core/image.h"
#include "core/math.h"

namespace fovrt {

inline constexpr float kFlipQc = 0.7f;
inline constexpr float kFlipQf = 0.5f;
inline constexpr float kFlipPc = 0.4f;
inline constexpr float kFlipPt = 0.95f;
inline constexpr float kFlipGw = 0.082f;  // peak-to-trough of the edge detector, degrees

// FLIP map of two display-encoded (sRGB, [0,1]) images at `pixelsPerDegree`.
Plane<float> FlipMapLdr(const Plane<vec3>& testSrgb, const Plane<vec3>& referenceSrgb, float pixelsPerDegree);
// FLIP map of two HDR images through fovrt's tonemap (tonemap.h).
Plane<float> FlipMap(const Plane<vec3>& test, const Plane<vec3>& reference, float pixelsPerDegree);
double Flip(const Plane<vec3>& test, const Plane<vec3>& reference, float pixelsPerDegree,
            const Plane<uint8_t>* mask = nullptr);

// Colour-only FLIP error of two uniform linear-RGB colours in [0,1] (no features, no filtering):
// what FlipMapLdr returns on two constant images. Exposed for tests and reports.
float FlipColorError(const vec3& testLinear, const vec3& referenceLinear);

}  // namespace fovrt
