// Image error metrics of fovrt (SPEC §8). Each metric has a per-pixel map and a masked mean, so a
// caller computes the maps once per (frame, eye, variant) and averages them over every region.
//
//   relMSE   mean over pixels and RGB channels of (y − r)² / (r² + ε), ε = 0.01, on HDR values.
//   SSIM     Wang et al. 2004 on the LUMA of the tonemapped image (tonemap.h):
//            Y' = 0.2126 R' + 0.7152 G' + 0.0722 B' of the display-encoded values, L = 1,
//            11×11 Gaussian window σ = 1.5, K1 = 0.01, K2 = 0.03. At the border the window is
//            cut to the image and renormalised, so the SSIM map covers every pixel.
//   FLIP     LDR-FLIP (flip.h).
//   temporal SVGF §5.4: per pixel |lum(frame_t) − lum(frame_{t−1})| on HDR Rec.709 luminance.
// Masks are Plane<uint8_t>, non-zero = inside; nullptr = whole image. The mean over an empty
// mask is NaN (callers drop it).
#pragma once

#include <cstdint>

#include "core/image.h"
#include "core/math.h"

namespace fovrt {

inline constexpr float kRelMseEpsilon = 0.01f;
inline constexpr int kSsimRadius = 5;  // 11×11 window
inline constexpr float kSsimSigma = 1.5f;
inline constexpr float kSsimK1 = 0.01f;
inline constexpr float kSsimK2 = 0.03f;

// Per-pixel relMSE, averaged over the three channels.
Plane<float> RelMseMap(const Plane<vec3>& test, const Plane<vec3>& reference,
                       float epsilon = kRelMseEpsilon);
double RelMse(const Plane<vec3>& test, const Plane<vec3>& reference,
              const Plane<uint8_t>* mask = nullptr, float epsilon = kRelMseEpsilon);

// Luma of the tonemapped image (what SSIM compares).
Plane<float> DisplayLuma(const Plane<vec3>& hdr);
// SSIM map of two single-channel images with values in [0, dynamicRange].
Plane<float> SsimMapOfLuma(const Plane<float>& test, const Plane<float>& reference,
                           float dynamicRange = 1.0f);
// SSIM map of two HDR images (tonemap, luma, then SsimMapOfLuma).
Plane<float> SsimMap(const Plane<vec3>& test, const Plane<vec3>& reference);
double Ssim(const Plane<vec3>& test, const Plane<vec3>& reference, const Plane<uint8_t>* mask = nullptr);

// |lum(current) − lum(previous)| per pixel, HDR.
Plane<float> TemporalErrorMap(const Plane<vec3>& current, const Plane<vec3>& previous);
double TemporalError(const Plane<vec3>& current, const Plane<vec3>& previous,
                     const Plane<uint8_t>* mask = nullptr);

// Mean of `map` over the pixels where mask != 0 (all pixels if mask is null); NaN when empty.
double MaskedMean(const Plane<float>& map, const Plane<uint8_t>* mask = nullptr);

}  // namespace fovrt
