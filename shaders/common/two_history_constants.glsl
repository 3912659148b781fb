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

// two_history_gradient: edge-aware filter of g, then q.
#define TH_GRADIENT_B_GRADIENT 0
#define TH_GRADIENT_B_ILLUM_U0 1
#define TH_GRADIENT_B_ILLUM_U1 2
#define TH_GRADIENT_B_GUIDE 3
#define TH_GRADIENT_B_DEPTH_GRAD 4
#define TH_GRADIENT_B_Q 5
#define TH_GRADIENT_BINDINGS 6

// two_history_blend: in place on the unweighted channel's à-trous output.
#define TH_BLEND_B_ILLUM_U 0   // vec4[N] read and written
#define TH_BLEND_B_ILLUM_W 1
#define TH_BLEND_B_WU 2
#define TH_BLEND_B_WW 3
#define TH_BLEND_B_S 4
#define TH_BLEND_B_Q 5
#define TH_BLEND_BINDINGS 6

// asvgf_gradient_claim: per sample, atomicMin of its index into its stratum's slot (the lowest
// index wins, as the C++ reference's "first sample wins").
#define ASVGF_CLAIM_B_SAMPLES 0   // GradientSample[count] (32 bytes each)
#define ASVGF_CLAIM_B_CLAIM 1     // uint[strata], 0xFFFFFFFF = empty
#define ASVGF_CLAIM_BINDINGS 2

// asvgf_gradient_gather: per stratum, (δ, Δ) and the stratum guide: the geometry and noisy
// luminance at its guide pixel (the claimed sample's pixel, else the stratum's centre), read once
// here instead of at every tap of every reconstruction iteration (AsvgfScatterGradientsRef's
// StratumGuide).
#define ASVGF_GATHER_B_SAMPLES 0
#define ASVGF_GATHER_B_CLAIM 1
#define ASVGF_GATHER_B_GRAD 2          // vec2[strata]
#define ASVGF_GATHER_B_GUIDE_GEOMETRY 3 // vec4[strata]: normal, depth (−1: background guide pixel)
#define ASVGF_GATHER_B_GUIDE_LUMINANCE 4 // vec4[strata]: noisy luminance, depth gradient, 0
#define ASVGF_GATHER_B_DEPTH 5          // per-pixel planes of this frame, read at the guide pixel
#define ASVGF_GATHER_B_NORMAL 6
#define ASVGF_GATHER_B_OBJECT 7
#define ASVGF_GATHER_B_DEPTH_GRAD 8
#define ASVGF_GATHER_B_DIRECT 9
#define ASVGF_GATHER_B_INDIRECT 10
#define ASVGF_GATHER_B_ALBEDO 11
#define ASVGF_GATHER_B_EMISSION 12
#define ASVGF_GATHER_BINDINGS 13

// asvgf_stratum_sigma: σ_l times the standard deviation of the guide luminance over the 3×3
// strata (the w_l scale of every reconstruction iteration; it does not depend on the step).
#define ASVGF_SIGMA_B_GUIDE_GEOMETRY 0
#define ASVGF_SIGMA_B_GUIDE_LUMINANCE 1
#define ASVGF_SIGMA_B_OUT 2             // float[strata]
#define ASVGF_SIGMA_BINDINGS 3

// asvgf_gradient_atrous: one 3×3-box iteration at stratum resolution.
#define ASVGF_ATROUS_B_GRAD_IN 0
#define ASVGF_ATROUS_B_GUIDE_GEOMETRY 1
#define ASVGF_ATROUS_B_GUIDE_LUMINANCE 2
#define ASVGF_ATROUS_B_SIGMA 3
#define ASVGF_ATROUS_B_GRAD_OUT 4
#define ASVGF_ATROUS_BINDINGS 5

// asvgf_alpha: per pixel α and λ.
#define ASVGF_ALPHA_B_GRAD 0
#define ASVGF_ALPHA_B_ALPHA 1
#define ASVGF_ALPHA_B_LAMBDA 2
#define ASVGF_ALPHA_BINDINGS 3

#endif
