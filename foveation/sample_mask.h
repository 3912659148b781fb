// Sample masks: how a pixel whose density d lies below one sample per pixel is traced on some
// frames only. A pixel's phase φ is its rank in an 8×8 ordered-dither (Bayer) matrix, (r + ½)/64;
// it is traced in frame t when ⌊φ + d(t+1)⌋ > ⌊φ + d·t⌋. For a pixel that keeps its d:
//   - over any T consecutive frames it is traced ⌊dT⌋ or ⌈dT⌉ times (a Sturmian sequence), so
//     the gap between two samples is ⌊1/d⌋ or ⌈1/d⌉ frames and every ⌈1/d⌉ frames hold one;
//   - its long-run rate is exactly d;
//   - in one frame the pixels of a region of equal d that are traced are those whose φ lies in an
//     interval of length d that slides by d each frame: ⌊64d⌋ or ⌈64d⌉ of every 8×8 tile, spread
//     as the dither spreads consecutive ranks (a lattice for d = 1/4, 1/16).
#pragma once

#include <cstdint>

namespace fovrt {

// The least density an spp map may ask for: a pixel is traced at least once every 16 frames.
inline constexpr float kMinSpp = 1.0f / 16.0f;

// The pixel's rank in the 8×8 Bayer matrix, 0..63 (consecutive ranks lie far apart).
uint32_t BayerRank8(int x, int y);
// Whether pixel (x, y) of density d in (0, 1) is traced in frame `frame` (see above).
bool SampleMaskSelects(float density, int x, int y, uint32_t frame);

}  // namespace fovrt
