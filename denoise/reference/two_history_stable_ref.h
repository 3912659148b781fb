// C++ reference of two-history-stable's stabilisation pass (shaders/two_history_stabilize.comp,
// denoise/two_history_stable.md): the filtered illumination of each channel gets a luminance
// history of its own, reprojected, clamped to the neighbourhood's spread and blended with a small
// weight, so that a pixel whose two-history blend jumps between the histories from frame to
// frame (a moving fovea changes its sample count) shows the jump spread over ~1/α_s frames. The
// per-pixel maths is shared with the tests and mirrored by shaders/common/two_history_stable.glsl.
#pragma once

#include <algorithm>

#include "core/frame_inputs.h"
#include "core/image.h"
#include "core/math.h"
#include "denoise/params.h"
#include "denoise/reference/svgf_ref.h"
#include "shaders/common/two_history_constants.glsl"

namespace fovrt {

// L_s = lerp(clamp(L_s,prev, m − kσ, m + kσ), L, max(α_s, 1/W_u)).
inline float StabilizedLuminance(float history, float l, float mean, float sigma, float k, float alphaS,
                                 float wu) {
    const float h = std::clamp(history, mean - k * sigma, mean + k * sigma);
    const float a = std::max(alphaS, 1.0f / std::max(wu, 1.0f));
    return h * (1.0f - a) + l * a;  // GLSL mix()
}

// The colour with luminance L_s and the hue of c (luminance L); shifted instead of scaled near black.
inline vec3 StabilizedColor(const vec3& c, float l, float ls) {
    return l > float(FOVRT_STABLE_LUMINANCE_FLOOR) ? c * (ls / l) : c + vec3(ls - l);
}

// Stage two_history_stabilize for one channel: `filtered` (illumination, variance) → `out`;
// `prevStable` (the previous frame's L_s, ignored without hasPrev) → `curStable`; `wu` this frame's W_u.
void TwoHistoryStabilizeRef(const Plane<vec4>& filtered, const FrameInputs& frame, const SvgfGeometry& prevGeometry,
                            bool hasPrev, const Plane<float>& prevStable, const Plane<float>& wu,
                            const TwoHistoryStableParams& params, Precision precision, Plane<float>& curStable,
                            Plane<vec4>& out);

}  // namespace fovrt
