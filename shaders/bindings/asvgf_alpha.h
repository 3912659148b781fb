// asvgf_alpha: per pixel α and λ from the reconstructed stratum gradient (δ̂, Δ̂).
#define ASVGF_ALPHA_BINDING_LIST(B)                       \
    B(ASVGF_ALPHA, GRAD, 0, TEXEL, RG32F, grad)           \
    B(ASVGF_ALPHA, ALPHA, 1, WRITE, float, alpha_out)     \
    B(ASVGF_ALPHA, LAMBDA, 2, WRITE, float, lambda_out)
