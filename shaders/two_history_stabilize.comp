#version 460
#extension GL_GOOGLE_include_directive : require
// two_history_stabilize — luminance stabilisation of one channel's filtered illumination
// (two-history-stable, denoise/two_history_stable.md). Mirrors TwoHistoryStabilizeRef.
// Purpose: L = lum(filtered); m, σ² = the 3×3 mean and variance of L over object pixels plus the
//   filtered variance estimate; L_s,prev reprojected with the bilinear taps of
//   common/own_history_reprojection.glsl (no 3×3 fallback: where they fail the stabilisation restarts);
//   L_s = lerp(clamp(L_s,prev, m ± kσ), L, max(α_s, 1/W_u, the antilag variant's change weight
//   from q)); out = the colour with luminance L_s.
// Reads:  filtered (illumination, variance), geometry of both frames, depth gradient, previous
//         pixel, W_u, the previous stabilised luminance.
// Writes: the stabilised (illumination, variance), this frame's stabilised luminance.
#include "shared_constants.h"
#include "push_constants.h"
#include "common/two_history_constants.glsl"
#include "common/packing.glsl"
#include "common/access.glsl"
#include "common/luminance.glsl"
#include "common/two_history_stable.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

FOVRT_DECLARE_BINDINGS(TH_STABILIZE_BINDING_LIST)  // shaders/bindings/two_history_stabilize.h

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_TWO_HISTORY_STABILIZE);  // shaders/push_constants.h

#include "common/own_history_reprojection.glsl"

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;
    vec4 c = FETCH4(illum_in, i);
    float l = luminance(c.rgb);

    // 3×3 luminance moments over object pixels (taps off the image or on background weigh 0).
    float sum = 0.0, sum2 = 0.0, count = 0.0;
    [[unroll]] for (int k = 0; k < 9; ++k) {
        ivec2 q = p + ivec2(k % 3 - 1, k / 3 - 1);
        int j = clamped_index(q, pc.size);
        float w = in_image(q, pc.size) && FETCH_OBJECT(object_id, j) != FOVRT_NO_OBJECT ? 1.0 : 0.0;
        float lq = luminance(FETCH4(illum_in, j).rgb);
        sum += w * lq;
        sum2 += w * lq * lq;
        count += w;
    }
    float mean = count > 0.0 ? sum / count : l;
    float spread = count > 0.0 ? max(0.0, sum2 / count - mean * mean) : 0.0;
    float sigma = sqrt(spread + max(c.a, 0.0));

    float ls = l;
    if (pc.has_prev != 0u) {
        ReprojTaps taps = own_history_taps(i, pc.size);
        if (taps.count > 0) {
            float history;
            REPROJ_GATHER(prev_stable, taps, pc.size, FETCH1, 0.0, history);
            float change = pc.antilag != 0u ? stabilization_change_weight(FETCH1(q, i), pc.antilag_q) : 0.0;
            ls = stabilized_luminance(history, l, mean, sigma, pc.sigma_scale,
                                      stabilization_weight(pc.alpha, FETCH1(wu, i), change));
        }
    }
    cur_stable[i] = hfloat(to_history(ls));
    illum_out[i] = TO_ILLUM(vec4(stabilized_color(c.rgb, l, ls), c.a));
}
