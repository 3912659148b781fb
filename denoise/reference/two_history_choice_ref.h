// C++ reference of the hysteresis variants' choice pass (shaders/two_history_choice.comp,
// denoise/two_history_stable.md): two-history's variance-optimal choice p, held against its own
// reprojected history by HystereticChoice (two_history_math.h), so that a p which jumps when the
// moving fovea changes a pixel's sample count moves the blend over ~1/rate frames instead of one.
#pragma once

#include "core/frame_inputs.h"
#include "core/image.h"
#include "core/math.h"
#include "denoise/params.h"
#include "denoise/reference/svgf_ref.h"

namespace fovrt {

// Stage two_history_choice: p from this frame's (W_u, W_w, S_k); `prevChoice` (the previous
// frame's held choice, ignored without hasPrev) reprojected with the bilinear taps; → `curChoice`.
// The held choice restarts at p where the taps fail or the accumulation restarted (W_u ≤ 1).
// ww and powerSums hold `window` (size 0: the image); outside it p = 1.
void TwoHistoryChoiceRef(const FrameInputs& frame, const SvgfGeometry& prevGeometry, bool hasPrev,
                         const Plane<float>& prevChoice, const Plane<float>& wu, const Plane<float>& ww,
                         const Plane<vec3>& powerSums, const TwoHistoryParams& params, Precision precision,
                         Plane<float>& curChoice, const HistoryWindow& window = {});

}  // namespace fovrt
