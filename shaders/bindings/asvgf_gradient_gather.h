// asvgf_gradient_gather: per stratum, (δ, Δ) and the stratum guide — geometry and noisy luminance
// at its guide pixel (the claimed sample's pixel, else the stratum's centre), read once here
// instead of at every tap of every reconstruction iteration. Per-pixel planes of this frame are
// read at the guide pixel only.
#define ASVGF_GATHER_BINDING_LIST(B)                                    \
    B(ASVGF_GATHER, SAMPLES, 0, READ, GradientSample, samples)          \
    B(ASVGF_GATHER, CLAIM, 1, READ, uint, claim)                        \
    B(ASVGF_GATHER, GRAD, 2, WRITE, vec2, grad)                         \
    B(ASVGF_GATHER, GUIDE_GEOMETRY, 3, WRITE, vec4, guide_geometry)     \
    B(ASVGF_GATHER, GUIDE_LUMINANCE, 4, WRITE, vec4, guide_luminance)   \
    B(ASVGF_GATHER, DEPTH, 5, DTEXEL, R32F, depth)                      \
    B(ASVGF_GATHER, NORMAL, 6, NTEXEL, RGB32F, normal)                  \
    B(ASVGF_GATHER, OBJECT, 7, OTEXEL, R32UI, object_id)               \
    B(ASVGF_GATHER, DEPTH_GRAD, 8, TEXEL, RG32F, depth_grad)            \
    B(ASVGF_GATHER, DIRECT, 9, HTEXEL, RGB32F, direct)                  \
    B(ASVGF_GATHER, INDIRECT, 10, HTEXEL, RGB32F, indirect)             \
    B(ASVGF_GATHER, ALBEDO, 11, HTEXEL, RGB32F, albedo)                 \
    B(ASVGF_GATHER, EMISSION, 12, HTEXEL, RGB32F, emission)
