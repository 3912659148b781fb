// two_history_reproject: temporal accumulation of both histories (SPEC §5; A-SVGF's per-pixel α,
// SPEC §4) for channel 0 (direct, or combined); PREV_IU_OTHER is the pair's channel-1 I_u. W_u
// lives in channel 0's "length" buffer, shared by both channels (PREV_WU2 and CUR_WU2 are bound
// unused). "two_history_reproject_pair" adds channel 1's planes.
#include "reprojection_inputs.h"
#define TH_REPROJECT_BINDING_LIST(B)                                \
    REPROJECT_INPUT_BINDINGS(B, TH_REPROJECT)                       \
    B(TH_REPROJECT, SAMPLE_COUNT, 12, READ, uint, sample_count)     \
    B(TH_REPROJECT, ALPHA, 13, READ, float, alpha_map)              \
    B(TH_REPROJECT, PREV_IU, 14, HTEXEL3, RGB32F, prev_iu0)         \
    B(TH_REPROJECT, PREV_IU_OTHER, 15, HTEXEL3, RGB32F, prev_iu1)   \
    B(TH_REPROJECT, PREV_IW, 16, HTEXEL3, RGB32F, prev_iw0)         \
    B(TH_REPROJECT, PREV_M, 17, HTEXEL, RG32F, prev_m0)             \
    B(TH_REPROJECT, PREV_WU, 18, HTEXEL, R32F, prev_wu0)            \
    B(TH_REPROJECT, PREV_WW, 19, HTEXEL, R32F, prev_ww)             \
    B(TH_REPROJECT, PREV_S, 20, HTEXEL3, RGB32F, prev_s)            \
    B(TH_REPROJECT, PREV_G, 21, HTEXEL, R32F, prev_g)               \
    B(TH_REPROJECT, CUR_IU, 22, WRITE, hfloat, cur_iu0)             \
    B(TH_REPROJECT, CUR_IW, 23, WRITE, hfloat, cur_iw0)             \
    B(TH_REPROJECT, CUR_M, 24, WRITE, hfloat, cur_m0)               \
    B(TH_REPROJECT, CUR_WU, 25, WRITE, hfloat, cur_wu0)             \
    B(TH_REPROJECT, CUR_WW, 26, WRITE, hfloat, cur_ww)              \
    B(TH_REPROJECT, CUR_S, 27, WRITE, hfloat, cur_s)                \
    B(TH_REPROJECT, CUR_G, 28, WRITE, hfloat, cur_g)                \
    B(TH_REPROJECT, ILLUM_U, 29, WRITE, hvec4, illum_u0)            \
    B(TH_REPROJECT, ILLUM_W, 30, WRITE, hvec4, illum_w0)            \
    B(TH_REPROJECT, STATS, 31, RW, uint, stats)
// Channel 1 of "two_history_reproject_pair".
#define TH_REPROJECT_PAIR_BINDING_LIST(B)                      \
    B(TH_REPROJECT, PREV_IW2, 32, HTEXEL3, RGB32F, prev_iw1)   \
    B(TH_REPROJECT, PREV_M2, 33, HTEXEL, RG32F, prev_m1)       \
    B(TH_REPROJECT, PREV_WU2, 34, HTEXEL, R32F, prev_wu1)      \
    B(TH_REPROJECT, CUR_IU2, 35, WRITE, hfloat, cur_iu1)       \
    B(TH_REPROJECT, CUR_IW2, 36, WRITE, hfloat, cur_iw1)       \
    B(TH_REPROJECT, CUR_M2, 37, WRITE, hfloat, cur_m1)         \
    B(TH_REPROJECT, CUR_WU2, 38, WRITE, hfloat, cur_wu1)       \
    B(TH_REPROJECT, ILLUM_U2, 39, WRITE, hvec4, illum_u1)      \
    B(TH_REPROJECT, ILLUM_W2, 40, WRITE, hvec4, illum_w1)
// Every binding of "two_history_reproject_pair".
#define TH_REPROJECT_PAIR_ALL_BINDING_LIST(B) TH_REPROJECT_BINDING_LIST(B) TH_REPROJECT_PAIR_BINDING_LIST(B)
