// two_history_blend: t = p + q − pq from (W_u, W_w, S_k) (the hysteresis variants: the held
// choice) and q, (I_u, Var) ← lerp(I_w, I_u, t) in place. The fp16 power sums stay a storage
// buffer (RGB16F texel buffers are rarely supported).
#define TH_BLEND_BINDING_LIST(B)                       \
    B(TH_BLEND, ILLUM_U, 0, RW, hvec4, illum_u)        \
    B(TH_BLEND, ILLUM_W, 1, HTEXEL, RGBA32F, illum_w)  \
    B(TH_BLEND, WU, 2, HTEXEL, R32F, wu)               \
    B(TH_BLEND, WW, 3, HTEXEL, R32F, ww)               \
    B(TH_BLEND, S, 4, HTEXEL3, RGB32F, s)              \
    B(TH_BLEND, Q, 5, TEXEL, R32F, q)                  \
    B(TH_BLEND, CHOICE, 6, HTEXEL, R32F, choice)
