// svgf_moments_classify: appends the pixels that need the spatial variance estimate (not
// background, history length < threshold) to a list, and counts the 1-D workgroups of
// svgf_filter_moments' indirect dispatch (lavapipe runs masked-off code anyway, so the 49-tap
// filter is dispatched only over the listed pixels; the rest is a buffer copy).
#define SVGF_CLASSIFY_BINDING_LIST(B)                           \
    B(SVGF_CLASSIFY, GUIDE, 0, TEXEL, RGBA32F, guide)           \
    B(SVGF_CLASSIFY, LENGTH, 1, HTEXEL, R32F, hist_length)      \
    B(SVGF_CLASSIFY, ARGS, 2, LIST, uint, list_args)            \
    B(SVGF_CLASSIFY, LIST, 3, LIST, uint, list_pixels)
