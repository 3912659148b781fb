#include "render/brdf_table.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/check.h"
#include "core/rng.h"
#include "render/sampler.h"

namespace fovrt {
namespace {

constexpr uint32_t kTableSeed = 0x46424554u;  // "FBET": scramble seeds of the table's entries

vec3 OutgoingDirection(float mu) {
    mu = std::clamp(mu, 0.0f, 1.0f);
    return vec3(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
}

// `samples` Owen-scrambled Sobol points mapped to the unit disk (VndfDiskPoint): the trigonometry
// of the VNDF sampler, done once for every entry that shares the point set.
std::vector<vec2> DiskPoints(uint32_t samples, uint32_t seed) {
    std::vector<vec2> disk(samples);
    for (uint32_t k = 0; k < samples; ++k) disk[k] = VndfDiskPoint(SobolOwen2D(seed, k, 0));
    return disk;
}

// A and B of (μ, alpha) over the disk points (the BSDF's own VNDF sampler): pdf(ω_i) =
// G1 D / (4μ), so the integrand D G2 / (4μ) has weight G2 / G1 = (1 + Λ_o) / (1 + Λ_o + Λ_i);
// reflections below the horizon add 0.
vec2 IntegrateSpecular(float mu, float alpha, const std::vector<vec2>& disk) {
    const vec3 wo = OutgoingDirection(mu);
    if (!(wo.z > 0.0f)) return vec2(0.0f);
    const float lambdaO = GgxLambda(alpha, wo.z);
    double a = 0.0, b = 0.0;
    for (const vec2& point : disk) {
        vec3 h = SampleGgxVndfDisk(alpha, wo, point);
        float woh = glm::dot(wo, h);
        vec3 wi = 2.0f * woh * h - wo;
        if (wi.z <= 0.0f) continue;
        float weight = (1.0f + lambdaO) / (1.0f + lambdaO + GgxLambda(alpha, wi.z));
        float s = SchlickWeight(std::max(woh, 0.0f));
        a += double((1.0f - s) * weight);
        b += double(s * weight);
    }
    return vec2(float(a / double(disk.size())), float(b / double(disk.size())));
}

}  // namespace

vec2 IntegrateSpecularChannels(float mu, float alpha, uint32_t samples, uint32_t seed) {
    FOVRT_CHECK_OP(samples, >, 0u);
    return IntegrateSpecular(mu, alpha, DiskPoints(samples, seed));
}

float IntegrateDiffuseChannel(float mu, uint32_t samples, uint32_t seed) {
    FOVRT_CHECK_OP(samples, >, 0u);
    const vec3 wo = OutgoingDirection(mu);
    // Cosine-distributed ω_i: (1/π) ∫ S cosθ_i dω_i = E[S].
    double c = 0.0;
    for (uint32_t k = 0; k < samples; ++k) {
        vec2 u = SobolOwen2D(seed, k, 0);
        float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
        vec3 wi(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u.x)));
        vec3 h = glm::normalize(wo + wi);
        c += double(SchlickWeight(std::max(glm::dot(wo, h), 0.0f)));
    }
    return float(c / samples);
}

BrdfTable BrdfTable::Build(int size, uint32_t specularSamples, uint32_t diffuseSamples) {
    FOVRT_CHECK_OP(size, >=, 2);
    auto start = std::chrono::steady_clock::now();
    BrdfTable t;
    t.size_ = size;
    t.texels_.assign(size_t(size) * size_t(size), BrdfChannels{});
    // One scrambled point set for every A/B entry: the entries' integration errors are then a
    // smooth function of (μ, r), not independent per-entry noise that remodulation would print
    // as a pattern (SPEC §6), and the disk mapping is done once.
    FOVRT_CHECK_OP(specularSamples, >, 0u);
    const std::vector<vec2> disk = DiskPoints(specularSamples, kTableSeed);
    tbb::parallel_for(0, size, [&](int i) {  // one μ column: C once, then A, B per roughness
        const float mu = t.TexelMu(i);
        const float c = IntegrateDiffuseChannel(mu, diffuseSamples, HashCombine(kTableSeed, uint32_t(i)));
        for (int j = 0; j < size; ++j) {
            const float alpha = GgxAlphaFromRoughness(t.TexelRoughness(j));
            const vec2 ab = IntegrateSpecular(mu, alpha, disk);
            t.texels_[size_t(j) * size_t(size) + size_t(i)] = BrdfChannels{ab.x, ab.y, c};
        }
    });
    t.buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return t;
}

BrdfChannels BrdfTable::Lookup(float mu, float roughness) const {
    // Between the edge texel centres and the domain's ends (half a texel) the lookup extrapolates
    // linearly instead of clamping: at μ = 1 or r = 1 the nearest centre is 1 − 1/512, and F_β at
    // r = 1 falls by ~0.6 per unit alpha (clamping would be 2.4e-3 off; the test checks 2e-3).
    auto axis = [&](float v, int& i0, int& i1, float& f) {
        float x = std::clamp(v, 0.0f, 1.0f) * float(size_) - 0.5f;
        i0 = std::clamp(int(std::floor(x)), 0, size_ - 2);
        i1 = i0 + 1;
        f = x - float(i0);  // in [-0.5, 1.5]
    };
    int i0, i1, j0, j1;
    float fx, fy;
    axis(mu, i0, i1, fx);
    axis(roughness, j0, j1, fy);
    auto mix = [&](float BrdfChannels::*ch) {
        float lo = Texel(i0, j0).*ch + (Texel(i1, j0).*ch - Texel(i0, j0).*ch) * fx;
        float hi = Texel(i0, j1).*ch + (Texel(i1, j1).*ch - Texel(i0, j1).*ch) * fx;
        return lo + (hi - lo) * fy;
    };
    return BrdfChannels{std::max(mix(&BrdfChannels::a), 0.0f), std::max(mix(&BrdfChannels::b), 0.0f),
                        std::max(mix(&BrdfChannels::c), 0.0f)};
}

const BrdfTable& SharedBrdfTable() {
    static const BrdfTable table = BrdfTable::Build();
    return table;
}

vec3 PreintegratedReflectance(const BrdfTable& table, const BsdfParams& p, float mu) {
    // The BSDF treats F0 = 0 as pure Lambert (no Fresnel at all): F_β = d.
    if (p.f0 == vec3(0.0f)) return p.diffuse;
    const BrdfChannels t = table.Lookup(mu, std::sqrt(p.alpha));
    return p.diffuse * (vec3(1.0f) - p.f0) * (1.0f - t.c) + p.f0 * t.a + vec3(t.b);
}

}  // namespace fovrt
