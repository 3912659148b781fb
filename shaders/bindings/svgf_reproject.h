// svgf_reproject: temporal accumulation of one channel (the colour, moments, length and — weighted
// mode — total-weight histories); "svgf_reproject_pair" adds the second channel's planes
// (FOVRT_CHANNELS 2; taps shared). Sample counts are packed uint16 pairs.
#include "reprojection_inputs.h"
#define SVGF_REPROJECT_BINDING_LIST(B)                                       \
    REPROJECT_INPUT_BINDINGS(B, SVGF_REPROJECT)                              \
    B(SVGF_REPROJECT, SAMPLE_COUNT, 12, READ, uint, sample_count)            \
    B(SVGF_REPROJECT, PREV_COLOR, 13, HTEXEL3, RGB32F, hist_prev_color0)     \
    B(SVGF_REPROJECT, PREV_MOMENTS, 14, HTEXEL, RG32F, hist_prev_moments0)   \
    B(SVGF_REPROJECT, PREV_LENGTH, 15, HTEXEL, R32F, hist_prev_length0)      \
    B(SVGF_REPROJECT, PREV_WEIGHT, 16, HTEXEL, R32F, hist_prev_weight0)      \
    B(SVGF_REPROJECT, CUR_COLOR, 17, WRITE, hfloat, hist_color0)             \
    B(SVGF_REPROJECT, CUR_MOMENTS, 18, WRITE, hfloat, hist_moments0)         \
    B(SVGF_REPROJECT, CUR_LENGTH, 19, WRITE, hfloat, hist_length0)           \
    B(SVGF_REPROJECT, CUR_WEIGHT, 20, WRITE, hfloat, hist_weight0)           \
    B(SVGF_REPROJECT, ILLUM_OUT, 21, WRITE, hvec4, illum_out0)               \
    B(SVGF_REPROJECT, STATS, 22, RW, uint, stats)
// The second channel of "svgf_reproject_pair".
#define SVGF_REPROJECT_PAIR_BINDING_LIST(B)                                   \
    B(SVGF_REPROJECT, PREV_COLOR2, 23, HTEXEL3, RGB32F, hist_prev_color1)     \
    B(SVGF_REPROJECT, PREV_MOMENTS2, 24, HTEXEL, RG32F, hist_prev_moments1)   \
    B(SVGF_REPROJECT, PREV_LENGTH2, 25, HTEXEL, R32F, hist_prev_length1)      \
    B(SVGF_REPROJECT, PREV_WEIGHT2, 26, HTEXEL, R32F, hist_prev_weight1)      \
    B(SVGF_REPROJECT, CUR_COLOR2, 27, WRITE, hfloat, hist_color1)             \
    B(SVGF_REPROJECT, CUR_MOMENTS2, 28, WRITE, hfloat, hist_moments1)         \
    B(SVGF_REPROJECT, CUR_LENGTH2, 29, WRITE, hfloat, hist_length1)           \
    B(SVGF_REPROJECT, CUR_WEIGHT2, 30, WRITE, hfloat, hist_weight1)           \
    B(SVGF_REPROJECT, ILLUM_OUT2, 31, WRITE, hvec4, illum_out1)
// Every binding of "svgf_reproject_pair".
#define SVGF_REPROJECT_PAIR_ALL_BINDING_LIST(B) SVGF_REPROJECT_BINDING_LIST(B) SVGF_REPROJECT_PAIR_BINDING_LIST(B)
