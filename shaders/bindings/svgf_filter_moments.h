// svgf_filter_moments (indirect, one invocation per pixel listed by svgf_moments_classify): the
// 7×7 spatial variance estimate; the other pixels were copied ILLUM_IN → ILLUM_OUT before.
#define SVGF_MOMENTS_BINDING_LIST(B)                            \
    B(SVGF_MOMENTS, ILLUM_IN, 0, HTEXEL, RGBA32F, illum_in)     \
    B(SVGF_MOMENTS, GUIDE, 1, TEXEL, RGBA32F, guide)            \
    B(SVGF_MOMENTS, DEPTH_GRAD, 2, TEXEL, RG32F, depth_grad)    \
    B(SVGF_MOMENTS, MOMENTS, 3, HTEXEL, RG32F, moments)         \
    B(SVGF_MOMENTS, LENGTH, 4, HTEXEL, R32F, hist_length)       \
    B(SVGF_MOMENTS, ILLUM_OUT, 5, WRITE, hvec4, illum_out)      \
    B(SVGF_MOMENTS, ARGS, 6, LIST, uint, list_args)             \
    B(SVGF_MOMENTS, LIST, 7, LIST, uint, list_pixels)
