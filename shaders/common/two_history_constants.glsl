// Bindings and push-constant flags of the two-history and A-SVGF shaders (shaders/two_history_*.comp,
// shaders/asvgf_*.comp). Macros only: included by GLSL and by C++ (denoise/vulkan/two_history_vk.cpp).
#ifndef FOVRT_TWO_HISTORY_CONSTANTS_GLSL
#define FOVRT_TWO_HISTORY_CONSTANTS_GLSL

// 1-D passes (one invocation per gradient sample).
#define FOVRT_WORKGROUP_1D 64

// two_history_reproject: one channel (combined: direct + indirect); two_history_reproject_pair:
// both channels in one dispatch (direct at the base bindings, indirect at COLOR_OTHER,
// PREV_IU_OTHER and the *2 bindings), with the taps and the per-pixel state (W_u, W_w, S_k, g)
// once per pixel (g: one float, the signed luminance of the gradient over both channels;
// two-history only, GRADIENT flag). Lavapipe allows 32 storage buffers per stage: the pair
// layout has 25 in fp16.
#define TH_REPROJECT_B_COLOR 0         // float[3N] channel 0's illumination (direct, or combined)
#define TH_REPROJECT_B_COLOR_OTHER 1   // float[3N] indirect (pair: channel 1; added when combined)
#define TH_REPROJECT_B_DEPTH 2
#define TH_REPROJECT_B_NORMAL 3
#define TH_REPROJECT_B_OBJECT 4
#define TH_REPROJECT_B_PREV_DEPTH 5
#define TH_REPROJECT_B_PREV_NORMAL 6
#define TH_REPROJECT_B_PREV_OBJECT 7
#define TH_REPROJECT_B_DEPTH_GRAD 8
#define TH_REPROJECT_B_PREV_PIXEL 9
#define TH_REPROJECT_B_LIST_ARGS 10    // uint[4] box-fallback list (as SVGF_REPROJECT_B_LIST_ARGS)
#define TH_REPROJECT_B_LIST 11         // uint[N]
#define TH_REPROJECT_B_SAMPLE_COUNT 12 // uint[N/2] packed uint16
#define TH_REPROJECT_B_ALPHA 13        // float[N] per-pixel α (A-SVGF)
#define TH_REPROJECT_B_PREV_IU 14      // previous frame's histories
#define TH_REPROJECT_B_PREV_IU_OTHER 15 // pair: channel 1's I_u
#define TH_REPROJECT_B_PREV_IW 16
#define TH_REPROJECT_B_PREV_M 17
#define TH_REPROJECT_B_PREV_WU 18      // the channel's "length" buffer holds W_u
#define TH_REPROJECT_B_PREV_WW 19
#define TH_REPROJECT_B_PREV_S 20
#define TH_REPROJECT_B_PREV_G 21
#define TH_REPROJECT_B_CUR_IU 22       // this frame's histories
#define TH_REPROJECT_B_CUR_IW 23
#define TH_REPROJECT_B_CUR_M 24
#define TH_REPROJECT_B_CUR_WU 25
#define TH_REPROJECT_B_CUR_WW 26
#define TH_REPROJECT_B_CUR_S 27
#define TH_REPROJECT_B_CUR_G 28
#define TH_REPROJECT_B_ILLUM_U 29      // vec4[N] (I_u, Var)
#define TH_REPROJECT_B_ILLUM_W 30      // vec4[N] (I_w, Var)
#define TH_REPROJECT_B_STATS 31
#define TH_REPROJECT_BINDINGS 32       // one channel ("two_history_reproject")
// Channel 1 of "two_history_reproject_pair".
#define TH_REPROJECT_B_PREV_IW2 32
#define TH_REPROJECT_B_PREV_M2 33
#define TH_REPROJECT_B_PREV_WU2 34
#define TH_REPROJECT_B_CUR_IU2 35
#define TH_REPROJECT_B_CUR_IW2 36
#define TH_REPROJECT_B_CUR_M2 37
#define TH_REPROJECT_B_CUR_WU2 38
#define TH_REPROJECT_B_ILLUM_U2 39
#define TH_REPROJECT_B_ILLUM_W2 40
#define TH_REPROJECT_PAIR_BINDINGS 41

// Mode bits of two_history_reproject, fixed per pipeline (specialization constant
// FOVRT_SPEC_REPROJECT_FLAGS); whether a previous frame exists is a push constant.
#define TH_REPROJECT_FLAG_TWO_HISTORY 1u   // accumulate I_w, W_w, S_k
#define TH_REPROJECT_FLAG_COMBINED 2u      // this channel = direct + indirect
#define TH_REPROJECT_FLAG_ALPHA_MAP 4u     // α from the per-pixel map
#define TH_REPROJECT_FLAG_WRITE_COLOR 8u   // feed back the unfiltered accumulation
#define TH_REPROJECT_FLAG_GRADIENT 16u     // accumulate g (two-history; not two-history-asvgf)


// ---- Bindings declared once (shaders/bindings.h) of the two-history and A-SVGF passes.
#include "../bindings.h"
#include "../bindings/asvgf_alpha.h"
#include "../bindings/asvgf_gradient_atrous.h"
#include "../bindings/asvgf_gradient_claim.h"
#include "../bindings/asvgf_gradient_gather.h"
#include "../bindings/asvgf_stratum_sigma.h"
#include "../bindings/two_history_blend.h"
#include "../bindings/two_history_gradient.h"
#ifdef __cplusplus
FOVRT_BINDING_CONSTANTS(TH_GRADIENT_BINDING_LIST)
FOVRT_BINDING_CONSTANTS(TH_BLEND_BINDING_LIST)
FOVRT_BINDING_CONSTANTS(ASVGF_CLAIM_BINDING_LIST)
FOVRT_BINDING_CONSTANTS(ASVGF_GATHER_BINDING_LIST)
FOVRT_BINDING_CONSTANTS(ASVGF_SIGMA_BINDING_LIST)
FOVRT_BINDING_CONSTANTS(ASVGF_ATROUS_BINDING_LIST)
FOVRT_BINDING_CONSTANTS(ASVGF_ALPHA_BINDING_LIST)
inline constexpr int TH_GRADIENT_BINDINGS = FOVRT_BINDING_COUNT(TH_GRADIENT_BINDING_LIST);
inline constexpr int TH_BLEND_BINDINGS = FOVRT_BINDING_COUNT(TH_BLEND_BINDING_LIST);
inline constexpr int ASVGF_CLAIM_BINDINGS = FOVRT_BINDING_COUNT(ASVGF_CLAIM_BINDING_LIST);
inline constexpr int ASVGF_GATHER_BINDINGS = FOVRT_BINDING_COUNT(ASVGF_GATHER_BINDING_LIST);
inline constexpr int ASVGF_SIGMA_BINDINGS = FOVRT_BINDING_COUNT(ASVGF_SIGMA_BINDING_LIST);
inline constexpr int ASVGF_ATROUS_BINDINGS = FOVRT_BINDING_COUNT(ASVGF_ATROUS_BINDING_LIST);
inline constexpr int ASVGF_ALPHA_BINDINGS = FOVRT_BINDING_COUNT(ASVGF_ALPHA_BINDING_LIST);
#endif

#endif
