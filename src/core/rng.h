// Deterministic hashing and per-pixel seeds. Seeds are a pure function of (eye, x, y, frame,
// sample), so images are bit-identical for any thread count and any tile order.
#pragma once

#include <cstdint>

namespace fovrt {

// PCG-style 32-bit integer hash (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering").
inline constexpr uint32_t HashPcg(uint32_t v) {
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

inline constexpr uint32_t HashCombine(uint32_t seed, uint32_t v) { return HashPcg(seed ^ (v + 0x9e3779b9u + (seed << 6) + (seed >> 2))); }

// The per-pixel seed of one frame: what the renderer's VisibilityBuffer::seed stores and A-SVGF
// re-uses.
inline constexpr uint32_t PixelSeed(uint32_t runSeed, uint32_t eye, uint32_t x, uint32_t y, uint32_t frame) {
    return HashCombine(HashCombine(HashCombine(HashCombine(HashPcg(runSeed), eye), x), y), frame);
}

// A small PCG32 generator for places that need a stream (e.g. picking random pixels per stratum).
class Pcg32 {
public:
    explicit Pcg32(uint64_t seed, uint64_t stream = 0x853c49e6748fea9bull) {
        inc_ = (stream << 1u) | 1u;
        Next();
        state_ += seed;
        Next();
    }
    uint32_t Next() {
        uint64_t old = state_;
        state_ = old * 6364136223846793005ull + inc_;
        uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        uint32_t rot = uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
    }
    // Uniform float in [0, 1).
    float NextFloat() { return float(Next() >> 8) * 0x1p-24f; }
    uint32_t NextBounded(uint32_t bound) { return uint32_t((uint64_t(Next()) * bound) >> 32); }

private:
    uint64_t state_ = 0;
    uint64_t inc_ = 0;
};

}  // namespace fovrt
