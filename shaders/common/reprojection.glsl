// Back-projection taps of temporal accumulation (SVGF §4.1, SPEC §3), shared by every stage that
// reprojects a history (svgf_reproject, two_history_reproject). The including shader defines
//   float reproj_prev_depth(int i); vec3 reproj_prev_normal(int i); uint reproj_prev_object(int i);
// (previous frame's planes, i = y·width + x). Mirrored by FindReprojectionTaps in denoise/reference/svgf_ref.cpp:
//   1. 2×2 bilinear taps around the previous continuous pixel; each tap must pass the consistency
//      test (same object id, |z_prev − z| / (dz + 0.01) ≤ 10, dot(n_prev, n) ≥ 0.9); weights of the
//      valid taps are renormalised.
//   2. If none is valid: every valid pixel of the 3×3 block around the nearest previous pixel,
//      equal weights.
//   3. Else: no tap (disocclusion or off-screen) → count = 0.
// Two passes, chosen at compile time by FOVRT_REPROJECT_BOX, because lavapipe runs every branch and
// every loop body under a lane mask even when no lane takes it (denoise/svgf.md): a 3×3 fallback
// inside the main pass cost 9 more consistency tests and 9 more taps per gathered plane on every
// pixel, for the few pixels that need it.
//   FOVRT_REPROJECT_BOX 0 (main pass, every pixel): step 1 only. Where it finds no tap on an
//     on-screen object pixel, taps.needs_box is set and count is 0: the pass writes the
//     disocclusion result and lists the pixel (common/pixel_list.glsl).
//   FOVRT_REPROJECT_BOX 1 (the "_box" variant, listed pixels only): step 2 only; it overwrites the
//     listed pixels' results (same arithmetic, other taps), so together the passes give 1–3.
// Taps are REPROJ_SLOTS fixed slots (bilinear 2×2 or the 3×3 box) so that an unrolled loop gathers
// them without dynamically indexed local arrays (slow on lavapipe):
//   [[unroll]] for (int t = 0; t < REPROJ_SLOTS; ++t) {
//       float w = reproj_tap_weight(taps, t);
//       if (w > 0.0) { int j = reproj_tap_index(taps, t, size); sum += w * value(j); } }
#ifndef FOVRT_REPROJECTION_GLSL
#define FOVRT_REPROJECTION_GLSL
#extension GL_EXT_control_flow_attributes : require
#include "shared_constants.h"

#ifndef FOVRT_REPROJECT_BOX
#define FOVRT_REPROJECT_BOX 0
#endif

float reproj_prev_depth(int i);
vec3 reproj_prev_normal(int i);
uint reproj_prev_object(int i);

#if FOVRT_REPROJECT_BOX
#define REPROJ_SLOTS 9
#else
#define REPROJ_SLOTS 4
#endif

struct ReprojTaps {
    int count;       // valid taps (0: disocclusion, or bilinear failed: see needs_box)
    ivec2 base;      // bilinear: top-left tap; box: centre pixel
    vec4 weight;     // bilinear: normalised weights, 0 for rejected taps
    uint mask;       // box: bit k set when pixel base + (k % 3 − 1, k / 3 − 1) is valid
    bool needs_box;  // main pass: no bilinear tap on an on-screen object pixel; the box pass decides
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
    taps.base = ivec2(0);
    taps.weight = vec4(0.0);
    taps.mask = 0u;
    taps.needs_box = false;
    if (id == FOVRT_NO_OBJECT) return taps;
    // Off-screen (and NaN, which fails every comparison) before any float → int conversion.
    if (!(all(greaterThan(prev_pixel, vec2(-1.0))) && all(lessThan(prev_pixel, vec2(size) + 1.0))))
        return taps;
#if FOVRT_REPROJECT_BOX
    taps.base = ivec2(floor(prev_pixel));
    [[unroll]] for (int k = 0; k < 9; ++k) {
        if (reproj_consistent(taps.base + ivec2(k % 3 - 1, k / 3 - 1), size, z, n, id, dz)) {
            taps.mask |= 1u << k;
            taps.count++;
        }
    }
#else
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
    } else {
        taps.weight = vec4(0.0);
        taps.count = 0;
        taps.needs_box = true;
    }
#endif
    return taps;
}

float reproj_tap_weight(ReprojTaps taps, int t) {
#if FOVRT_REPROJECT_BOX
    return (taps.mask & (1u << t)) != 0u ? 1.0 / float(taps.count) : 0.0;
#else
    return taps.weight[t];
#endif
}

// The previous-frame pixel of tap slot t.
ivec2 reproj_tap_pixel(ReprojTaps taps, int t) {
#if FOVRT_REPROJECT_BOX
    return taps.base + ivec2(t % 3 - 1, t / 3 - 1);
#else
    return taps.base + ivec2(t & 1, t >> 1);
#endif
}

int reproj_tap_index(ReprojTaps taps, int t, ivec2 size) {
    ivec2 q = reproj_tap_pixel(taps, t);
    return q.y * size.x + q.x;
}

// Weighted gather of one plane over the taps (GLSL cannot pass buffer arrays): `load(arr, j)` is
// a macro or function reading pixel j, e.g. REPROJ_GATHER(hist, taps, size, LOAD3, vec3(0.0), out).
#define REPROJ_GATHER(arr, taps, size, load, zero, out_)                             \
    do {                                                                           \
        out_ = zero;                                                               \
        [[unroll]] for (int t_ = 0; t_ < REPROJ_SLOTS; ++t_) {                     \
            float w_ = reproj_tap_weight(taps, t_);                                \
            if (w_ > 0.0) out_ += w_ * load(arr, reproj_tap_index(taps, t_, size));   \
        }                                                                          \
    } while (false)

// The path-sample count n a reprojection stage accumulates pixel i with (`counts`: the packed
// uint16 sample counts, common/packing.glsl): the count itself where the stage weighs by it
// (`weighs`: svgf-weighted, the two-history variants); where it only needs to know whether the
// pixel had a sample (`zero_aware`: the unweighted stages when the spp map may hold zeros), 0 or
// 1, so that a sampled pixel's arithmetic is the one without counts; else 1 (nothing is read).
// n = 0 keeps the reprojected history as it is. Mirrored by ReprojectionSampleCount
// (denoise/reference/svgf_ref.h).
#define REPROJ_SAMPLE_COUNT(counts, i, weighs, zero_aware) \
    ((weighs) ? float(LOAD_U16(counts, i)) : ((zero_aware) && LOAD_U16(counts, i) == 0u) ? 0.0 : 1.0)

#endif
