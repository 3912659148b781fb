// BRDF pre-integration F_β (Zhuang et al., "Real-time Denoising Using BRDF Pre-integration
// Factorization", Eq. 7; SPEC §6) of fovrt's own BSDF (render/bsdf.h): the directional albedo
// F_β(ω_o) = ∫ f_r cosθ_i dω_i that the tracer demodulates by when render.demodulation = "brdf".
//
// Schlick's F = F0 (1 − S) + S is linear in F0, so for Lambert·(1 − F) + GGX the integral splits
// into three tables of (μ = cosθ_o, roughness) that hold for every base colour and metallic:
//   F_β = d ⊙ (1 − F0) ⊙ (1 − C(μ)) + F0 ⊙ A(μ, r) + B(μ, r)          (exact, per channel)
//   A = ∫ (1 − S) D G2 / (4μ) dω_i,  B = ∫ S D G2 / (4μ) dω_i,  C = (1/π) ∫ S cosθ_i dω_i,
// with S = (1 − ω_o·h)⁵, d the diffuse colour. A material with F0 = 0 is pure Lambert in the
// BSDF (no specular interface, F = 0), so its F_β is d (PreintegratedReflectance says so too).
//
// The table: 256 × 256 texels at texel centres μ_i = (i + ½)/256, r_j = (j + ½)/256; roughness r
// maps to alpha = max(r², kMinGgxAlpha) exactly as MakeBsdfParams does, and lookups index by
// r = sqrt(alpha), so a clamped alpha lands on table rows with the same alpha. Each A/B entry
// integrates 1024 Owen-scrambled Sobol points (render/sampler.h) through the BSDF's own VNDF
// sampler (weight G2/G1, S from SchlickWeight), the same scrambled point set for every entry;
// C (no roughness dependence) integrates 16384 cosine-distributed points per μ. Plain Monte
// Carlo with 1024 samples would leave ~1 % noise per entry, which remodulation turns into a
// pattern (SPEC §6). Lookups are bilinear, extrapolated linearly over the half texel between the
// edge texel centres and the domain's ends. Built once per process, on first use, in parallel
// (TBB).
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"
#include "render/bsdf.h"

namespace fovrt {

// The three pre-integrated channels at one (μ, roughness).
struct BrdfChannels {
    float a = 0.0f;  // ∫ (1 − S) D G2 / (4μ) dω_i
    float b = 0.0f;  // ∫ S D G2 / (4μ) dω_i
    float c = 0.0f;  // (1/π) ∫ S cosθ_i dω_i
};

class BrdfTable {
public:
    static constexpr int kSize = 256;                 // texels along μ and along roughness
    static constexpr uint32_t kSpecularSamples = 1024;  // Sobol points per A/B entry
    static constexpr uint32_t kDiffuseSamples = 16384;  // Sobol points per C(μ)

    // Integrates every entry (TBB over μ rows). `size` and the sample counts are for tests.
    static BrdfTable Build(int size = kSize, uint32_t specularSamples = kSpecularSamples,
                           uint32_t diffuseSamples = kDiffuseSamples);

    int size() const { return size_; }
    // The entry at texel (i along μ, j along roughness).
    const BrdfChannels& Texel(int i, int j) const { return texels_[size_t(j) * size_t(size_) + size_t(i)]; }
    // μ and roughness of a texel centre.
    float TexelMu(int i) const { return (float(i) + 0.5f) / float(size_); }
    float TexelRoughness(int j) const { return (float(j) + 0.5f) / float(size_); }
    // Bilinear lookup at μ = cosθ_o and roughness, both clamped to [0, 1] (linear extrapolation
    // over the outer half texels; results clamped at 0).
    BrdfChannels Lookup(float mu, float roughness) const;
    // Wall-clock seconds Build() took.
    double buildSeconds() const { return buildSeconds_; }

private:
    int size_ = 0;
    std::vector<BrdfChannels> texels_;
    double buildSeconds_ = 0.0;
};

// The process's table at full size, built on the first call (thread-safe); every renderer
// shares it.
const BrdfTable& SharedBrdfTable();

// One entry's integrals (what Build() computes per texel), for tests: A and B of (μ, alpha)
// with `samples` Owen-scrambled Sobol points (scramble seed `seed`), C of μ likewise.
vec2 IntegrateSpecularChannels(float mu, float alpha, uint32_t samples, uint32_t seed);
float IntegrateDiffuseChannel(float mu, uint32_t samples, uint32_t seed);

// F_β of the BSDF `params` at outgoing cosine μ (SPEC §6 formula; d for pure Lambert, F0 = 0).
// Not clamped: F_β can exceed 1 at grazing angles (white dielectric, μ = 0.2, r = 0.05: ~1.3);
// the tracer clamps it below only, as it clamps the albedo.
vec3 PreintegratedReflectance(const BrdfTable& table, const BsdfParams& params, float mu);

}  // namespace fovrt
