// asvgf_gradient_atrous: one à-trous iteration of (δ, Δ) at stratum resolution.
#define ASVGF_ATROUS_BINDING_LIST(B)                                       \
    B(ASVGF_ATROUS, GRAD_IN, 0, TEXEL, RG32F, grad_in)                     \
    B(ASVGF_ATROUS, GUIDE_GEOMETRY, 1, TEXEL, RGBA32F, guide_geometry)     \
    B(ASVGF_ATROUS, GUIDE_LUMINANCE, 2, TEXEL, RGBA32F, guide_luminance)   \
    B(ASVGF_ATROUS, SIGMA, 3, TEXEL, R32F, sigma_l)                        \
    B(ASVGF_ATROUS, GRAD_OUT, 4, WRITE, vec2, grad_out)
