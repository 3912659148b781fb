// two_history_stabilize: luminance stabilisation of one channel's filtered illumination
// (two-history-stable). Reads the filtered (illumination, variance), this frame's geometry and the
// previous frame's (the stabilised history's bilinear reprojection), W_u (the warm-up), the
// previous stabilised luminance, q (two-history-stable-antilag; unused otherwise); writes the
// stabilised illumination and this frame's luminance.
#define TH_STABILIZE_BINDING_LIST(B)                             \
    B(TH_STABILIZE, ILLUM_IN, 0, HTEXEL, RGBA32F, illum_in)      \
    B(TH_STABILIZE, ILLUM_OUT, 1, WRITE, hvec4, illum_out)       \
    B(TH_STABILIZE, DEPTH, 2, DTEXEL, R32F, depth)               \
    B(TH_STABILIZE, NORMAL, 3, NTEXEL, RGB32F, normal)           \
    B(TH_STABILIZE, OBJECT, 4, OTEXEL, R32UI, object_id)        \
    B(TH_STABILIZE, PREV_DEPTH, 5, DTEXEL, R32F, prev_depth)     \
    B(TH_STABILIZE, PREV_NORMAL, 6, NTEXEL, RGB32F, prev_normal) \
    B(TH_STABILIZE, PREV_OBJECT, 7, OTEXEL, R32UI, prev_object) \
    B(TH_STABILIZE, DEPTH_GRAD, 8, TEXEL, RG32F, depth_grad)     \
    B(TH_STABILIZE, PREV_PIXEL, 9, TEXEL, RG32F, prev_pixel)     \
    B(TH_STABILIZE, WU, 10, HTEXEL, R32F, wu)                    \
    B(TH_STABILIZE, PREV_STABLE, 11, HTEXEL, R32F, prev_stable)  \
    B(TH_STABILIZE, CUR_STABLE, 12, WRITE, hfloat, cur_stable)   \
    B(TH_STABILIZE, Q, 13, TEXEL, R32F, q)
