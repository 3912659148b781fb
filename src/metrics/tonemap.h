// The one display transform every LDR metric (SSIM, FLIP) and every report image uses.
//
// fovrt's tonemap is "clamp, then sRGB encode": display = SrgbEncode(clamp(hdr, 0, 1)) per channel,
// exposure 1. It is exactly invertible on [0,1], so FLIP's own sRGB→linear step recovers
// clamp(hdr, 0, 1), and closed-form tests stay simple. Values above 1 clip (as on the display).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/image.h"
#include "core/math.h"
#include "shaders/common/display_transform.glsl"

namespace fovrt {

// sRGB OETF (IEC 61966-2-1), linear [0,1] -> encoded [0,1]: the display transform's, written once
// for C++ and GLSL (shaders/common/display_transform.glsl; PNG output and the live preview use it).
inline float SrgbEncode(float linear) { return glsl::fovrt_srgb_encode(linear); }
// sRGB EOTF, encoded [0,1] -> linear [0,1].
inline float SrgbDecode(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

inline vec3 ToneMap(const vec3& hdr) {
    auto channel = [](float v) { return SrgbEncode(std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f); };
    return vec3(channel(hdr.r), channel(hdr.g), channel(hdr.b));
}

inline Plane<vec3> ToneMap(const Plane<vec3>& hdr) {
    Plane<vec3> out(hdr.width(), hdr.height());
    for (size_t i = 0; i < hdr.size(); ++i) out[i] = ToneMap(hdr[i]);
    return out;
}

}  // namespace fovrt
