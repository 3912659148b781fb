#version 460
#extension GL_GOOGLE_include_directive : require
// two_history_blend — the variance-optimal, gradient-guided blend of the two histories after
// à-trous iteration 1 (SPEC §5). Mirrors TwoHistoryBlendRef.
// Purpose: p from (W_u, W_w, S_k); t = p + q − pq; out = lerp((I_w, Var_w), (I_u, Var_u), t).
// The clamp variants (pc.clamp_history) replace p by the box of I_w's 3×3 mean ± kσ
// (two_history_clamp_blend); I_w is read-only, so the neighbours' reads race with no write.
// The hysteresis variants (pc.held_choice) read p from two_history_choice's held choice.
// Outside the weighted history's window (pc.win_size at pc.win_origin) t = 1: I_u is kept as it is.
// Reads:  filtered (I_u, Var) and (I_w, Var), W_u, W_w, power sums (in the window), q, the held choice.
// Writes: the blend, in place over (I_u, Var) (the input of the remaining iterations).
#include "shared_constants.h"
#include "push_constants.h"
#include "common/two_history_constants.glsl"
#include "common/packing.glsl"
#include "common/access.glsl"
#include "common/two_history.glsl"
#include "common/history_window.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

FOVRT_DECLARE_BINDINGS(TH_BLEND_BINDING_LIST)  // shaders/bindings/two_history_blend.h
#ifdef FOVRT_FP16
#define LOAD_S(i) LOAD3(s, i)
#else
#define LOAD_S(i) FETCH3(s, i)
#endif

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_TWO_HISTORY_BLEND);  // shaders/push_constants.h

// Mean and σ per component of I_w over p's in-image 3×3 neighbourhood (NeighbourhoodMeanSigma).
void neighbourhood_mean_sigma(ivec2 p, out vec3 mean, out vec3 sigma) {
    vec3 sum = vec3(0.0), sum_sq = vec3(0.0);
    float count = 0.0;
    for (int d = 0; d < 9; ++d) {
        ivec2 n = p + ivec2(d % 3 - 1, d / 3 - 1);
        if (any(lessThan(n, ivec2(0))) || any(greaterThanEqual(n, pc.size))) continue;
        vec3 c = FETCH4(illum_w, n.y * pc.size.x + n.x).rgb;
        sum += c;
        sum_sq += c * c;
        count += 1.0;
    }
    mean = sum / count;
    sigma = sqrt(max(sum_sq / count - mean * mean, vec3(0.0)));
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    int i = p.y * pc.size.x + p.x;
    int wi = window_index(p, pc.win_origin, pc.win_size);
    if (wi < 0) return;  // no weighted history here: the unweighted one, as it is
    if (pc.clamp_history != 0u) {
        vec3 mean, sigma;
        neighbourhood_mean_sigma(p, mean, sigma);
        illum_u[i] = TO_ILLUM(two_history_clamp_blend(vec4(illum_u[i]), FETCH4(illum_w, i), mean, sigma,
                                                      pc.clamp_sigma, FETCH1(q, i)));
        return;
    }
    float pb = pc.held_choice != 0u ? FETCH1(choice, i)
                                    : two_history_optimal_blend(FETCH1(wu, i), FETCH1(ww, wi), LOAD_S(wi));
    float qi = FETCH1(q, i);
    float t = pb + qi - pb * qi;
    illum_u[i] = TO_ILLUM(mix(FETCH4(illum_w, i), vec4(illum_u[i]), t));
}
