// Constants shared by the C++ host code and the GLSL shaders (included by both; macros only, so
// it parses as C++ and as GLSL). Dispatch sizes, binding indices and caps derive from here.
#ifndef FOVRT_SHARED_CONSTANTS_H
#define FOVRT_SHARED_CONSTANTS_H

// Workgroup of every 2-D image pass: 64×1 invocations (rows). On lavapipe (8-wide subgroups)
// 64×1 measured faster than 8×8 for the texel-buffer gathers (denoise/svgf.md, "Speed").
#define FOVRT_WORKGROUP_X 64
#define FOVRT_WORKGROUP_Y 1

// fp16 storage saturates finite values at ±this (below the largest half, 65504) instead of
// letting them round to ±inf: the shaders' to_history, the reference's QuantizeHistory, the
// host's colour-input conversion (QuantizeInput).
#define FOVRT_HALF_SATURATION 65000.0
// History length cap (frames). α = max(α, 1/length) makes lengths beyond 1/α irrelevant.
#define FOVRT_MAX_HISTORY_LENGTH 64.0
// Reprojection consistency tests (SPEC §3, Falcor): reject a tap when
// |z_prev − z| / (dz + 0.01) > 10, or when dot(n_prev, n) < cos threshold.
#define FOVRT_REPROJECT_DEPTH_TOLERANCE 10.0
#define FOVRT_REPROJECT_DEPTH_EPSILON 0.01
#define FOVRT_REPROJECT_NORMAL_COS 0.9
// Bilinear weights below this sum count as "no valid tap" (falls back to the 3×3 search).
#define FOVRT_REPROJECT_MIN_WEIGHT 0.001
// Epsilons of the à-trous weights (SPEC §3) and albedo floor of demodulation (Falcor 1e-3).
#define FOVRT_ATROUS_DEPTH_EPSILON 1e-4
#define FOVRT_ATROUS_LUMINANCE_EPSILON 1e-10
// Specialization constant (constant_id) of the edge-stopping shaders: k ≥ 0 when σn = 2^k, so that
// w_n = max(0, n·n')^σn is k squarings instead of exp2(σn·log2(n·n')) (a log2 per tap is ~1/5 of an
// à-trous pass on lavapipe); −1 = any other σn, evaluated with log2. Set by the host from σn
// (NormalWeightSquarings in denoise/svgf_family_plan.h). Up to 2^12 = 4096.
#define FOVRT_SPEC_NORMAL_SQUARINGS 0
#define FOVRT_MAX_NORMAL_SQUARINGS 12
// Specialization constant (constant_id) of the reprojection shaders: their mode bits
// (SVGF_REPROJECT_FLAG_*, TH_REPROJECT_FLAG_*), fixed per pipeline. As push-constant flags the code
// they switch off still ran (lavapipe executes both sides of a branch); as a specialization
// constant it is folded away when the pipeline is created.
#define FOVRT_SPEC_REPROJECT_FLAGS 1
// Specialization constant (constant_id, bool) of svgf_atrous: this iteration writes the colour
// history (the feedback iteration). A push-constant flag cost the masked stores on every iteration.
#define FOVRT_SPEC_ATROUS_WRITE_HISTORY 2
// Specialization constant (constant_id, bool) of svgf_modulate: one channel holds direct + indirect.
#define FOVRT_SPEC_MODULATE_COMBINED 3
// Specialization constant (constant_id, bool) of svgf_atrous, for the bench's floor probe only
// (denoise/bench/atrous_probe.h): every edge-stopping weight is 1, so the dispatch keeps its fetches and
// sums and loses the weight arithmetic. Never set by a denoiser.
#define FOVRT_SPEC_ATROUS_UNIT_WEIGHTS 4
// Specialization constant (constant_id, bool) of asvgf_alpha: the anti-lag variants' output, the
// anti-lag factor a = clamp(gain·λ, 0, 1) instead of A-SVGF's α.
#define FOVRT_SPEC_ASVGF_ANTILAG 5
// 7×7 spatial variance estimate radius.
#define FOVRT_MOMENTS_RADIUS 3
// Maximum à-trous iterations (SvgfParams::atrousIterations range).
#define FOVRT_MAX_ATROUS_ITERATIONS 8
// Object id of background pixels (matches fovrt::kNoObject).
#define FOVRT_NO_OBJECT 0xFFFFFFFFu
// Low mantissa bits of a packed depth that hold the object id in fp16 storage (common/depth_id.glsl).
#define FOVRT_DEPTH_ID_BITS 9u
// The variance of an (illumination, variance) plane at a pixel that holds nothing: no path sample
// this frame (sample count 0) and no history to keep. Every real variance is >= 0; the spatial
// passes give such a pixel weight 0, so its neighbours fill it (HOLDS_NOTHING, HoldsNothing).
#define FOVRT_EMPTY_VARIANCE (-1.0)

// ---- Bindings (set 0), one list per shader --------------------------------------------------
// Per-pixel planes are tightly packed arrays indexed i = y·width + x: RGB as 3 floats, vec2 as 2.
// History planes ("hfloat") are float, or float16_t in the _fp16 variants.
// svgf_reproject's bindings: shaders/bindings/svgf_reproject.h.
// Mode bits (FOVRT_SPEC_REPROJECT_FLAGS)
#define SVGF_REPROJECT_FLAG_WEIGHTED 1u    // svgf-weighted: W ← (1−α)W + n, C += n(x − C)/W
#define SVGF_REPROJECT_FLAG_COMBINED 2u    // one channel = direct + indirect
#define SVGF_REPROJECT_FLAG_WRITE_COLOR 4u // write the colour history (no à-trous feedback)
#define SVGF_REPROJECT_FLAG_ZERO_SAMPLES 8u // unweighted, read n only for n = 0 (maps below 1 spp)

// bandwidth_copy (src/vk/bandwidth.cpp): bindings in shaders/bindings/bandwidth_copy.h.
#define BANDWIDTH_EXP2_PER_ELEMENT 64     // exp2 per element of the ALU probe (multiple of 4)

#define FOVRT_SPATIAL_LIST_GROUP 64        // invocations per workgroup of the list dispatch
// Cap of a list dispatch's group count along x (Vulkan guarantees 65535); longer lists (above
// 4.19 MPix, e.g. 2064×2208 per eye) take further rows of groups along y (common/pixel_list.glsl).
#define FOVRT_SPATIAL_LIST_MAX_GROUPS 65535u

#define FOVRT_ATROUS_BLOCK_Y 2             // an invocation filters 2×this pixels at stride step (1: measured slower on lavapipe)
// ---- Bindings declared once (shaders/bindings.h): one list per pass, GLSL and C++ alike.
#include "bindings.h"
#include "bindings/svgf_atrous.h"
#include "bindings/svgf_filter_moments.h"
#include "bindings/svgf_modulate.h"
#include "bindings/svgf_moments_classify.h"
#include "bindings/svgf_pack_guide.h"
#include "bindings/svgf_reproject.h"
#include "bindings/bandwidth_copy.h"
#include "bindings/rae.h"
#ifdef __cplusplus
FOVRT_PASS_BINDINGS(SVGF_REPROJECT)  // one channel ("svgf_reproject")
FOVRT_PAIR_BINDINGS(SVGF_REPROJECT)  // "svgf_reproject_pair"
FOVRT_PASS_BINDINGS(SVGF_GUIDE)
FOVRT_PASS_BINDINGS(SVGF_CLASSIFY)
FOVRT_PASS_BINDINGS(SVGF_MOMENTS)
FOVRT_PASS_BINDINGS(SVGF_ATROUS)  // "svgf_atrous"
FOVRT_PAIR_BINDINGS(SVGF_ATROUS)  // "svgf_atrous_pair"
FOVRT_PASS_BINDINGS(SVGF_MODULATE)
FOVRT_PASS_BINDINGS(BANDWIDTH)
FOVRT_PASS_BINDINGS(RAE_CONV)
FOVRT_PASS_BINDINGS(RAE_POOL)
#endif

#endif
