// Back-projection taps of temporal accumulation (SVGF §4.1, SPEC §3), shared by every stage that
// reprojects a history (svgf_reproject, two-history, A-SVGF). The including shader defines
//   float reproj_prev_depth(int i); vec3 reproj_prev_normal(int i); uint reproj_prev_object(int i);
// (previous frame's planes, i = y·width + x). Mirrored by FindReprojectionTaps in denoise/svgf_ref.cpp.
//   1. 2×2 bilinear taps around the previous continuous pixel; each tap must pass the consistency
//      test (same object id, |z_prev − z| / (dz + 0.01) ≤ 10, dot(n_prev, n) ≥ 0.9); weights of the
//      valid taps are renormalised.
//   2. If none is valid: every valid pixel of the 3×3 block around the nearest previous pixel,
//      equal weights.
//   3. Else: no tap (disocclusion or off-screen) → count = 0.
// Taps are REPROJ_SLOTS fixed slots (0–3 bilinear, 4–12 the 3×3 box) so that an unrolled loop
// gathers them without dynamically indexed local arrays (slow on lavapipe):
//   [[unroll]] for (int t = 0; t < REPROJ_SLOTS; ++t) {
//       float w = reproj_tap_weight(taps, t);
//       if (w > 0.0) { int j = reproj_tap_index(taps, t, size); sum += w * value(j); } }
#ifndef FOVRT_REPROJECTION_GLSL
#define FOVRT_REPROJECTION_GLSL
#extension GL_EXT_control_flow_attributes : require
#include "shared_constants.h"

float reproj_prev_depth(int i);
vec3 reproj_prev_normal(int i);
uint reproj_prev_object(int i);

#define REPROJ_SLOTS 13

struct ReprojTaps {
    int count;      // valid taps (0: disocclusion)
    bool bilinear;  // slots 0–3 in use (else slots 4–12)
    ivec2 base;     // bilinear: top-left tap; box: centre pixel
    vec4 weight;    // normalised bilinear weights, 0 for rejected taps
    uint mask;      // box: bit k set when pixel base + (k % 3 − 1, k / 3 − 1) is valid
};

bool reproj_consistent(ivec2 q, ivec2 size, float z, vec3 n, uint id, float dz) {
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) return false;
    int j = q.y * size.x + q.x;
    if (reproj_prev_object(j) != id) return false;
    float z_prev = reproj_prev_depth(j);
    if (abs(z_prev - z) / (dz + FOVRT_REPROJECT_DEPTH_EPSILON) > FOVRT_REPROJECT_DEPTH_TOLERANCE)
        return false;
    return dot(reproj_prev_normal(j), n) >= FOVRT_REPROJECT_NORMAL_COS;
}

// prev_pixel: continuous previous-frame position (pixel centres at +0.5). dz = max(|∂z/∂x|, |∂z/∂y|).
ReprojTaps find_reprojection_taps(vec2 prev_pixel, ivec2 size, float z, vec3 n, uint id, float dz) {
    ReprojTaps taps;
    taps.count = 0;
    taps.bilinear = true;
    taps.base = ivec2(0);
    taps.weight = vec4(0.0);
    taps.mask = 0u;
    if (id == FOVRT_NO_OBJECT) return taps;
    // Off-screen (and NaN, which fails every comparison) before any float → int conversion.
    if (!(all(greaterThan(prev_pixel, vec2(-1.0))) && all(lessThan(prev_pixel, vec2(size) + 1.0))))
        return taps;
    vec2 pos = prev_pixel - 0.5;
    taps.base = ivec2(floor(pos));
    vec2 f = pos - vec2(taps.base);
    vec4 bilinear = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
    float sum = 0.0;
    [[unroll]] for (int t = 0; t < 4; ++t) {
        if (bilinear[t] > 0.0 && reproj_consistent(taps.base + ivec2(t & 1, t >> 1), size, z, n, id, dz)) {
            taps.weight[t] = bilinear[t];
            sum += bilinear[t];
            taps.count++;
        }
    }
    if (sum >= FOVRT_REPROJECT_MIN_WEIGHT) {
        taps.weight /= sum;
        return taps;
    }
    taps.bilinear = false;
    taps.weight = vec4(0.0);
    taps.count = 0;
    taps.base = ivec2(floor(prev_pixel));
    // A loop run at most once rather than an if: lavapipe executes both sides of a branch under
    // a lane mask, but skips a loop whose trip count is 0 on every lane.
    [[dont_unroll]] for (int once = 0; once < (sum >= FOVRT_REPROJECT_MIN_WEIGHT ? 0 : 1); ++once) {
        [[unroll]] for (int k = 0; k < 9; ++k) {
            if (reproj_consistent(taps.base + ivec2(k % 3 - 1, k / 3 - 1), size, z, n, id, dz)) {
                taps.mask |= 1u << k;
                taps.count++;
            }
        }
    }
    return taps;
}

float reproj_tap_weight(ReprojTaps taps, int t) {
    if (t < 4) return taps.bilinear ? taps.weight[t] : 0.0;
    return (!taps.bilinear && (taps.mask & (1u << (t - 4))) != 0u) ? 1.0 / float(taps.count) : 0.0;
}

int reproj_tap_index(ReprojTaps taps, int t, ivec2 size) {
    ivec2 q = t < 4 ? taps.base + ivec2(t & 1, t >> 1) : taps.base + ivec2((t - 4) % 3 - 1, (t - 4) / 3 - 1);
    return q.y * size.x + q.x;
}

// Weighted gather of one plane over the taps (GLSL cannot pass buffer arrays): `load(arr, j)` is
// a macro or function reading pixel j, e.g. REPROJ_GATHER(hist, taps, size, LOAD3, vec3(0.0), out).
#define REPROJ_LOAD1(arr, j) float((arr)[j])
#define REPROJ_GATHER(arr, taps, size, load, zero, out_)                             \
    do {                                                                           \
        out_ = zero;                                                               \
        [[unroll]] for (int t_ = 0; t_ < 4; ++t_) {                                \
            float w_ = reproj_tap_weight(taps, t_);                                \
            if (w_ > 0.0) out_ += w_ * load(arr, reproj_tap_index(taps, t_, size));   \
        }                                                                          \
        [[dont_unroll]] for (int o_ = 0; o_ < (taps.bilinear ? 0 : 1); ++o_) {    \
            [[unroll]] for (int t_ = 4; t_ < REPROJ_SLOTS; ++t_) {                 \
                float w_ = reproj_tap_weight(taps, t_);                            \
                if (w_ > 0.0) out_ += w_ * load(arr, reproj_tap_index(taps, t_, size)); \
            }                                                                      \
        }                                                                          \
    } while (false)

#endif
