// The inputs every reprojection shader (svgf_reproject, two_history_reproject) binds at the same
// slots 0–11, for the pass prefix P: both colour channels (COLOR_IN2 is added when combined, or
// is the pair's second channel), the geometry of this frame and the previous one, depth gradient
// and motion, and the list of the pixels whose bilinear taps all failed (the box-fallback pass;
// common/pixel_list.glsl declares it).
#define REPROJECT_INPUT_BINDINGS(B, P)                 \
    B(P, COLOR_IN, 0, HTEXEL, RGB32F, color_in)        \
    B(P, COLOR_IN2, 1, HTEXEL, RGB32F, color_in2)      \
    B(P, DEPTH, 2, DTEXEL, R32F, depth)                \
    B(P, NORMAL, 3, NTEXEL, RGB32F, normal)            \
    B(P, OBJECT, 4, OTEXEL, R32UI, object_id)         \
    B(P, PREV_DEPTH, 5, DTEXEL, R32F, prev_depth)      \
    B(P, PREV_NORMAL, 6, NTEXEL, RGB32F, prev_normal)  \
    B(P, PREV_OBJECT, 7, OTEXEL, R32UI, prev_object)  \
    B(P, DEPTH_GRAD, 8, TEXEL, RG32F, depth_grad)      \
    B(P, PREV_PIXEL, 9, TEXEL, RG32F, prev_pixel)      \
    B(P, LIST_ARGS, 10, LIST, uint, list_args)         \
    B(P, LIST, 11, LIST, uint, list_pixels)
