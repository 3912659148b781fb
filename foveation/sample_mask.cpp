#include "foveation/sample_mask.h"

#include <cmath>

namespace fovrt {

uint32_t BayerRank8(int x, int y) {
    // Bit-interleave (x ⊕ y, y), lowest bit first into the highest pair: the recursive Bayer
    // matrix [[0, 2], [3, 1]] at every scale.
    const uint32_t a = uint32_t(x ^ y), b = uint32_t(y);
    uint32_t rank = 0;
    for (int bit = 0; bit < 3; ++bit) rank = (rank << 2) | (((a >> bit) & 1u) << 1) | ((b >> bit) & 1u);
    return rank;
}

bool SampleMaskSelects(float density, int x, int y, uint32_t frame) {
    const double phase = (double(BayerRank8(x, y)) + 0.5) / 64.0;
    const double d = double(density), start = phase + d * double(frame);
    return std::floor(start + d) > std::floor(start);
}

}  // namespace fovrt
