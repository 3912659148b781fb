#version 460
#extension GL_GOOGLE_include_directive : require
// two_history_choice — the hysteresis variants' temporally filtered, hysteretic history choice
// (denoise/two_history_stable.md). Mirrors TwoHistoryChoiceRef.
// Purpose: p from (W_u, W_w, S_k) as two_history_blend evaluates it; the previous held choice
//   reprojected with the bilinear taps of common/own_history_reprojection.glsl; held =
//   hysteretic_choice(prev, p, rate, band). Where the taps fail, on the first frame, or where the
//   accumulation restarted (W_u ≤ 1) the held choice restarts at p.
// Outside the weighted history's window (pc.win_size at pc.win_origin) p = 1, as the blend keeps I_u there.
// Reads:  geometry of both frames, depth gradient, previous pixel, W_u, W_w, power sums, the
//         previous held choice.
// Writes: this frame's held choice (two_history_blend reads it in place of p).
#include "shared_constants.h"
#include "push_constants.h"
#include "common/two_history_constants.glsl"
#include "common/packing.glsl"
#include "common/access.glsl"
#include "common/two_history.glsl"
#include "common/history_window.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

FOVRT_DECLARE_BINDINGS(TH_CHOICE_BINDING_LIST)  // shaders/bindings/two_history_choice.h
#ifdef FOVRT_FP16
#define LOAD_S(i) LOAD3(s, i)
#else
#define LOAD_S(i) FETCH3(s, i)
#endif

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_TWO_HISTORY_CHOICE);  // shaders/push_constants.h

#include "common/own_history_reprojection.glsl"

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;
    float wu = FETCH1(wu, i);
    int wi = window_index(p, pc.win_origin, pc.win_size);
    float pb = wi < 0 ? 1.0 : two_history_optimal_blend(wu, FETCH1(ww, wi), LOAD_S(wi));
    float held = pb;
    if (pc.has_prev != 0u && wu > 1.0) {
        ReprojTaps taps = own_history_taps(i, pc.size);
        if (taps.count > 0) {
            float prev;
            REPROJ_GATHER(prev_choice, taps, pc.size, FETCH1, 0.0, prev);
            held = hysteretic_choice(prev, pb, pc.rate, pc.band);
        }
    }
    cur_choice[i] = hfloat(to_history(held));
}
