// Low-discrepancy sampling addressed by the per-pixel seed: Owen-scrambled Sobol (0,2)-sequence in
// 2D pairs with a per-pair hashed index shuffle (Burley 2020, "Practical Hash-based Owen
// Scrambling"). Sample i of a pixel with seed s in dimension pair d depends only on (s, i, d), so
// re-shading with a stored seed reproduces the exact random numbers (A-SVGF §3.2).
#pragma once

#include <bit>
#include <cstdint>

#include "core/math.h"
#include "core/rng.h"

namespace fovrt {

inline uint32_t ReverseBits(uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
    x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
    return (x >> 16) | (x << 16);
}

// Laine-Karras style hash: each bit depends only on lower bits (a nested uniform scramble when
// applied to bit-reversed digits).
inline uint32_t LaineKarrasPermutation(uint32_t x, uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

inline uint32_t NestedUniformScramble(uint32_t x, uint32_t seed) {
    return ReverseBits(LaineKarrasPermutation(ReverseBits(x), seed));
}

// First two Sobol dimensions as 0.32 fixed point.
inline uint32_t SobolDim0(uint32_t i) { return ReverseBits(i); }
inline uint32_t SobolDim1(uint32_t i) {
    uint32_t r = 0;
    for (uint32_t v = 1u << 31; i != 0; i >>= 1, v ^= v >> 1)
        if (i & 1u) r ^= v;
    return r;
}

namespace detail {
// Sobol dimension 1 is linear over GF(2): ReverseBits(SobolDim1(i)) is the XOR of four byte
// tables, one per byte of i (the hot path avoids the 32-step loop).
struct RevSobol1Tables {
    uint32_t t[4][256];
    constexpr RevSobol1Tables() : t{} {
        uint32_t dir[32] = {};
        uint32_t v = 1u << 31;
        for (int k = 0; k < 32; ++k, v ^= v >> 1) {
            uint32_t r = 0;  // bit-reverse v
            for (int b = 0; b < 32; ++b)
                if (v & (1u << b)) r |= 1u << (31 - b);
            dir[k] = r;
        }
        for (int byte = 0; byte < 4; ++byte)
            for (int value = 0; value < 256; ++value) {
                uint32_t x = 0;
                for (int bit = 0; bit < 8; ++bit)
                    if (value & (1 << bit)) x ^= dir[byte * 8 + bit];
                t[byte][value] = x;
            }
    }
};
inline constexpr RevSobol1Tables kRevSobol1{};
inline uint32_t RevSobolDim1(uint32_t i) {
    return kRevSobol1.t[0][i & 255u] ^ kRevSobol1.t[1][(i >> 8) & 255u] ^
           kRevSobol1.t[2][(i >> 16) & 255u] ^ kRevSobol1.t[3][i >> 24];
}
}  // namespace detail

inline float ToUnitFloat(uint32_t x) { return float(x >> 8) * 0x1p-24f; }  // in [0, 1)

// 2D point of dimension pair `pair` for a sample whose bit-reversed index is `reversedIndex`.
// Equal to: shuffled = NestedUniformScramble(index, pairSeed);
//           x = NestedUniformScramble(SobolDim0(shuffled), seed1), y = ...(SobolDim1(shuffled), seed2),
// with the back-to-back bit reversals cancelled.
inline vec2 SobolOwen2DReversed(uint32_t pixelSeed, uint32_t reversedIndex, uint32_t pair) {
    uint32_t pairSeed = HashCombine(pixelSeed, pair);
    uint32_t shuffled = ReverseBits(LaineKarrasPermutation(reversedIndex, pairSeed));
    uint32_t x = ReverseBits(LaineKarrasPermutation(shuffled, HashCombine(pairSeed, 1u)));
    uint32_t y = ReverseBits(LaineKarrasPermutation(detail::RevSobolDim1(shuffled), HashCombine(pairSeed, 2u)));
    return vec2(ToUnitFloat(x), ToUnitFloat(y));
}

// 2D point `index` of dimension pair `pair` for a pixel seed.
inline vec2 SobolOwen2D(uint32_t pixelSeed, uint32_t index, uint32_t pair) {
    return SobolOwen2DReversed(pixelSeed, ReverseBits(index), pair);
}

// Per-pixel part of the sampler: the scramble seeds of each dimension pair depend only on the
// pixel seed, so they are hashed once per pixel instead of once per sample.
class PixelSampler {
public:
    static constexpr uint32_t kCachedPairs = 24;  // 8 path vertices; further pairs are hashed on use
    static constexpr uint32_t kAllPairs = (1u << kCachedPairs) - 1u;
    // pairMask: bit p set = prepare dimension pair p (p < kCachedPairs); the others are hashed on use.
    explicit PixelSampler(uint32_t pixelSeed, uint32_t pairMask = kAllPairs)
        : seed_(pixelSeed), cached_(pairMask & kAllPairs) {
        for (uint32_t m = cached_; m != 0; m &= m - 1u) {
            uint32_t pair = uint32_t(std::countr_zero(m));
            seeds_[pair] = Seeds(pair);
        }
    }
    // Same value as SobolOwen2DReversed(pixelSeed, reversedIndex, pair).
    vec2 Get(uint32_t reversedIndex, uint32_t pair) const {
        uvec3 s = pair < kCachedPairs && (cached_ >> pair) & 1u ? seeds_[pair] : Seeds(pair);
        uint32_t shuffled = ReverseBits(LaineKarrasPermutation(reversedIndex, s.x));
        uint32_t x = ReverseBits(LaineKarrasPermutation(shuffled, s.y));
        uint32_t y = ReverseBits(LaineKarrasPermutation(detail::RevSobolDim1(shuffled), s.z));
        return vec2(ToUnitFloat(x), ToUnitFloat(y));
    }

private:
    uvec3 Seeds(uint32_t pair) const {
        uint32_t pairSeed = HashCombine(seed_, pair);
        return uvec3(pairSeed, HashCombine(pairSeed, 1u), HashCombine(pairSeed, 2u));
    }
    uint32_t seed_;
    uint32_t cached_;  // bit p: seeds_[p] holds pair p's seeds
    uvec3 seeds_[kCachedPairs];
};

// The random numbers one path sample draws, dimension pairs laid out per path vertex.
class PathSampler {
public:
    PathSampler(const PixelSampler& pixel, uint32_t sampleIndex)
        : pixel_(pixel), reversedIndex_(ReverseBits(sampleIndex)) {}
    // Pairs per vertex: light position, (light select, lobe select), BSDF direction.
    static constexpr uint32_t kPairsPerVertex = 3;
    vec2 LightPoint(int vertex) const { return Get(uint32_t(vertex) * kPairsPerVertex + 0); }
    vec2 Selectors(int vertex) const { return Get(uint32_t(vertex) * kPairsPerVertex + 1); }
    vec2 BsdfDirection(int vertex) const { return Get(uint32_t(vertex) * kPairsPerVertex + 2); }

private:
    vec2 Get(uint32_t pair) const { return pixel_.Get(reversedIndex_, pair); }
    const PixelSampler& pixel_;
    uint32_t reversedIndex_;
};

}  // namespace fovrt
