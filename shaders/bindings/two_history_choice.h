// two_history_choice: the hysteresis variants' held history choice. Reads this frame's geometry and
// the previous frame's (the held choice's bilinear reprojection), W_u, W_w and the power sums (p),
// the previous held choice; writes this frame's.
#define TH_CHOICE_BINDING_LIST(B)                             \
    B(TH_CHOICE, DEPTH, 0, DTEXEL, R32F, depth)               \
    B(TH_CHOICE, NORMAL, 1, NTEXEL, RGB32F, normal)           \
    B(TH_CHOICE, OBJECT, 2, OTEXEL, R32UI, object_id)        \
    B(TH_CHOICE, PREV_DEPTH, 3, DTEXEL, R32F, prev_depth)     \
    B(TH_CHOICE, PREV_NORMAL, 4, NTEXEL, RGB32F, prev_normal) \
    B(TH_CHOICE, PREV_OBJECT, 5, OTEXEL, R32UI, prev_object) \
    B(TH_CHOICE, DEPTH_GRAD, 6, TEXEL, RG32F, depth_grad)     \
    B(TH_CHOICE, PREV_PIXEL, 7, TEXEL, RG32F, prev_pixel)     \
    B(TH_CHOICE, WU, 8, HTEXEL, R32F, wu)                     \
    B(TH_CHOICE, WW, 9, HTEXEL, R32F, ww)                     \
    B(TH_CHOICE, S, 10, HTEXEL3, RGB32F, s)                   \
    B(TH_CHOICE, PREV_CHOICE, 11, HTEXEL, R32F, prev_choice)  \
    B(TH_CHOICE, CUR_CHOICE, 12, WRITE, hfloat, cur_choice)
