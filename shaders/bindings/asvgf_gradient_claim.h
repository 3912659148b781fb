// asvgf_gradient_claim: per sample, atomicMin of its index into its stratum's slot (the lowest
// index wins, as the C++ reference's "first sample wins"); 0xFFFFFFFF = empty.
#define ASVGF_CLAIM_BINDING_LIST(B)                             \
    B(ASVGF_CLAIM, SAMPLES, 0, READ, GradientSample, samples)   \
    B(ASVGF_CLAIM, CLAIM, 1, RW, uint, claim)
