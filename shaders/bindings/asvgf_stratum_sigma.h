// asvgf_stratum_sigma: σ_l·std of the stratum guide's luminance, once per frame.
#define ASVGF_SIGMA_BINDING_LIST(B)                                       \
    B(ASVGF_SIGMA, GUIDE_GEOMETRY, 0, TEXEL, RGBA32F, guide_geometry)     \
    B(ASVGF_SIGMA, GUIDE_LUMINANCE, 1, TEXEL, RGBA32F, guide_luminance)   \
    B(ASVGF_SIGMA, OUT, 2, WRITE, float, sigma_out)
