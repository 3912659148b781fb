// two_history_gradient: edge-aware 5×5 filter of the EMA gradient g (its luminance), then q from
// each channel's variance.
#define TH_GRADIENT_BINDING_LIST(B)                           \
    B(TH_GRADIENT, GRADIENT, 0, HTEXEL, R32F, gradient)       \
    B(TH_GRADIENT, ILLUM_U0, 1, HTEXEL, RGBA32F, illum_u0)    \
    B(TH_GRADIENT, ILLUM_U1, 2, HTEXEL, RGBA32F, illum_u1)    \
    B(TH_GRADIENT, GUIDE, 3, TEXEL, RGBA32F, guide)           \
    B(TH_GRADIENT, DEPTH_GRAD, 4, TEXEL, RG32F, depth_grad)   \
    B(TH_GRADIENT, Q, 5, WRITE, float, q_out)
