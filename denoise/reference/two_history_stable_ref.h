// C++ reference of two-history-stable's stabilisation pass (shaders/two_history_stabilize.comp,
// denoise/two_history_stable.md): the filtered illumination of each channel gets a luminance
// history of its own, reprojected, clamped to the neighbourhood's spread and blended with a small
// weight, so that a pixel whose two-history blend jumps between the histories from frame to
// frame (a moving fovea changes its sample count) shows the jump spread over ~1/α_s frames. The
// per-pixel maths is the shader's own text (shaders/common/two_history_stable.glsl), called here
// under the names the tests use.
#pragma once

#include <algorithm>

#include "core/frame_inputs.h"
#include "core/image.h"
#include "core/math.h"
#include "denoise/params.h"
#include "denoise/reference/svgf_ref.h"
#include "shaders/common/two_history_stable.glsl"

namespace fovrt {

// The stabilisation weight: α_s, raised to 1/W_u while the accumulation warms up. `changeWeight`
// (two-history-stable-antilag's StabilizationChangeWeight, else 0) raises it where the light changes.
inline float StabilizationWeight(float alphaS, float wu, float changeWeight) {
    return glsl::stabilization_weight(alphaS, wu, changeWeight);
}

// two-history-stable-antilag: (q − q0)/(1 − q0), clamped to [0, 1]. q, two-history's change
// detector (S·|g| / std(lum I_u)), stays below ~0.5 on a static view's noise and reaches 1 where
// the light changes faster than the noise hides (a sliding penumbra).
inline float StabilizationChangeWeight(float q, float q0) {
    return glsl::stabilization_change_weight(q, q0);
}

// L_s = lerp(clamp(L_s,prev, m − kσ, m + kσ), L, a), a the StabilizationWeight.
inline float StabilizedLuminance(float history, float l, float mean, float sigma, float k, float a) {
    return glsl::stabilized_luminance(history, l, mean, sigma, k, a);
}

// The colour with luminance L_s and the hue of c (luminance L); shifted instead of scaled near black.
inline vec3 StabilizedColor(const vec3& c, float l, float ls) {
    return glsl::stabilized_color(c, l, ls);
}

// Stage two_history_stabilize for one channel: `filtered` (illumination, variance) → `out`;
// `prevStable` (the previous frame's L_s, ignored without hasPrev) → `curStable`; `wu` this frame's W_u;
// `q` two-history's change detector for two-history-stable-antilag (nullptr: the weight ignores change).
void TwoHistoryStabilizeRef(const Plane<vec4>& filtered, const FrameInputs& frame, const SvgfGeometry& prevGeometry,
                            bool hasPrev, const Plane<float>& prevStable, const Plane<float>& wu,
                            const TwoHistoryStableParams& params, Precision precision, Plane<float>& curStable,
                            Plane<vec4>& out, const Plane<float>* q = nullptr);

}  // namespace fovrt
