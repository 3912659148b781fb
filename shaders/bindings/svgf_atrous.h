// svgf_atrous: one à-trous iteration of one illumination channel ("svgf_atrous"); the pair
// variant ("svgf_atrous_pair", FOVRT_CHANNELS 2) adds the second channel's planes after them and
// shares the guide and depth gradient. The colour history is written on the feedback iteration.
#define SVGF_ATROUS_BINDING_LIST(B)                               \
    B(SVGF_ATROUS, ILLUM_IN, 0, HTEXEL, RGBA32F, illum_in0)       \
    B(SVGF_ATROUS, GUIDE, 1, TEXEL, RGBA32F, guide)               \
    B(SVGF_ATROUS, DEPTH_GRAD, 2, TEXEL, RG32F, depth_grad)       \
    B(SVGF_ATROUS, ILLUM_OUT, 3, WRITE, hvec4, illum_out0)        \
    B(SVGF_ATROUS, HIST_COLOR, 4, WRITE, hfloat, hist_color0)
#define SVGF_ATROUS_PAIR_BINDING_LIST(B)                          \
    B(SVGF_ATROUS, ILLUM_IN2, 5, HTEXEL, RGBA32F, illum_in1)      \
    B(SVGF_ATROUS, ILLUM_OUT2, 6, WRITE, hvec4, illum_out1)       \
    B(SVGF_ATROUS, HIST_COLOR2, 7, WRITE, hfloat, hist_color1)
// Every binding of "svgf_atrous_pair".
#define SVGF_ATROUS_PAIR_ALL_BINDING_LIST(B) SVGF_ATROUS_BINDING_LIST(B) SVGF_ATROUS_PAIR_BINDING_LIST(B)
