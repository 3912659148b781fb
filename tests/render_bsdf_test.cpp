// BSDF sampling agrees with evaluation: the sampled weights f cos / pdf average to the albedo
// obtained by quadrature of EvalBsdf, and the pdf integrates to one over the hemisphere.
#include <cmath>

#include "core/rng.h"
#include "render/bsdf.h"
#include "render/sampler.h"
#include "test_support.h"

using namespace fovrt;

namespace {

struct Quadrature {
    vec3 albedo = vec3(0.0f);
    float pdfIntegral = 0.0f;
};

Quadrature Integrate(const BsdfParams& p, const vec3& wo) {
    const int nt = 1024, np = 256;
    Quadrature q;
    for (int i = 0; i < nt; ++i) {
        float theta = (i + 0.5f) / nt * (kPi / 2.0f);
        for (int j = 0; j < np; ++j) {
            float phi = (j + 0.5f) / np * 2.0f * kPi;
            vec3 wi(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            float dw = std::sin(theta) * (kPi / 2.0f / nt) * (2.0f * kPi / np);
            BsdfEval e = EvalBsdf(p, wo, wi);
            q.albedo += e.fCos * dw;
            q.pdfIntegral += e.pdf * dw;
        }
    }
    return q;
}

// Mean sampled weight; `failed`: fraction of samples that produced no direction (specular
// microfacet reflections below the horizon), which is the pdf mass missing from the hemisphere.
vec3 SampledAlbedo(const BsdfParams& p, const vec3& wo, int n, float& failed) {
    vec3 sum(0.0f);
    int fails = 0;
    for (int i = 0; i < n; ++i) {
        vec2 u = SobolOwen2D(1234u, uint32_t(i), 0);
        vec2 sel = SobolOwen2D(1234u, uint32_t(i), 1);
        BsdfSample s;
        if (SampleBsdf(p, wo, u, sel.x, s))
            sum += s.weight;
        else
            ++fails;
    }
    failed = float(fails) / float(n);
    return sum / float(n);
}

}  // namespace

TEST_CASE("BSDF sampling is consistent with evaluation", "[render]") {
    struct Case {
        vec3 base;
        float roughness, metallic, specular;
    };
    for (const Case& c : {Case{vec3(0.8f, 0.5f, 0.2f), 1.0f, 0.0f, 0.0f}, Case{vec3(0.8f), 0.5f, 0.0f, 1.0f},
                          Case{vec3(0.9f, 0.7f, 0.4f), 0.3f, 1.0f, 1.0f}, Case{vec3(0.5f), 0.6f, 0.5f, 1.0f}}) {
        BsdfParams p = MakeBsdfParams(c.base, c.roughness, c.metallic, c.specular);
        for (float cosO : {1.0f, 0.7f, 0.3f}) {
            vec3 wo(std::sqrt(1.0f - cosO * cosO), 0.0f, cosO);
            Quadrature q = Integrate(p, wo);
            float failed = 0.0f;
            vec3 sampled = SampledAlbedo(p, wo, 1 << 16, failed);
            INFO("roughness " << c.roughness << " metallic " << c.metallic << " cosO " << cosO);
            CHECK(q.pdfIntegral + failed == Approx(1.0f).epsilon(0.01));
            for (int k = 0; k < 3; ++k) {
                CHECK(sampled[k] == Approx(q.albedo[k]).epsilon(0.02));
                CHECK(q.albedo[k] <= 1.0f);
            }
        }
    }
}

TEST_CASE("pure Lambert has albedo equal to the base colour", "[render]") {
    BsdfParams p = MakeBsdfParams(vec3(0.25f, 0.5f, 0.75f), 1.0f, 0.0f, 0.0f);
    Quadrature q = Integrate(p, vec3(0, 0, 1));
    CHECK(q.albedo.x == Approx(0.25f).epsilon(1e-3));
    CHECK(q.albedo.z == Approx(0.75f).epsilon(1e-3));
}

TEST_CASE("Owen-scrambled Sobol points are stratified and seed dependent", "[render]") {
    // 16 points of a (0,2)-sequence: exactly one per cell of a 4x4 grid.
    for (uint32_t seed : {1u, 99u}) {
        int cells[16] = {};
        for (uint32_t i = 0; i < 16; ++i) {
            vec2 u = SobolOwen2D(seed, i, 3);
            REQUIRE(u.x >= 0.0f);
            REQUIRE(u.x < 1.0f);
            ++cells[int(u.y * 4) * 4 + int(u.x * 4)];
        }
        for (int c : cells) CHECK(c == 1);
    }
    CHECK(SobolOwen2D(1u, 0, 0) != SobolOwen2D(2u, 0, 0));
    CHECK(SobolOwen2D(1u, 5, 0) == SobolOwen2D(1u, 5, 0));
}

TEST_CASE("the fast Sobol-Owen path equals the plain nested-scramble definition", "[render]") {
    for (uint32_t seed : {3u, 0xdeadbeefu})
        for (uint32_t pair : {0u, 5u})
            for (uint32_t i : {0u, 1u, 2u, 7u, 100u, 65535u}) {
                uint32_t pairSeed = HashCombine(seed, pair);
                uint32_t shuffled = NestedUniformScramble(i, pairSeed);
                uint32_t x = NestedUniformScramble(SobolDim0(shuffled), HashCombine(pairSeed, 1u));
                uint32_t y = NestedUniformScramble(SobolDim1(shuffled), HashCombine(pairSeed, 2u));
                vec2 fast = SobolOwen2D(seed, i, pair);
                CHECK(fast.x == ToUnitFloat(x));
                CHECK(fast.y == ToUnitFloat(y));
                PixelSampler pixel(seed);
                CHECK(pixel.Get(ReverseBits(i), pair) == fast);
                CHECK(pixel.Get(ReverseBits(i), pair + PixelSampler::kCachedPairs) ==
                      SobolOwen2D(seed, i, pair + PixelSampler::kCachedPairs));
                // Prepared or hashed on use, a pair gives the same point.
                for (uint32_t mask : {0u, 1u << pair, ~(1u << pair)})
                    CHECK(PixelSampler(seed, mask).Get(ReverseBits(i), pair) == fast);
            }
}
