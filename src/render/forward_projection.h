// A-SVGF forward projection (Schied et al. 2018, §3 "Constructing Gradient Samples"): what the
// tracer keeps of an eye's previous frame, and the merge of forward-projected previous surface
// samples into the new visibility buffer. A merged pixel holds the previous frame's surface
// sample (not at its centre), seed and sample count n_prev, and is shaded once like every other
// pixel: its colour is this frame's sample of the pixel and f_i(G→, ξ_{i−1}); no extra shading,
// but the frame traces Σ (n_prev − n_cur) samples more or fewer than the spp map says
// (sampleCount records what was traced).
#pragma once

#include <cstdint>

#include "core/camera.h"
#include "core/frame_inputs.h"
#include "render/embree_scene.h"
#include "render/visibility_buffer.h"

namespace fovrt {

// What A-SVGF's forward projection reads of one eye's previous frame besides its visibility buffer.
struct EyeHistory {
    bool valid = false;
    uint32_t frame = 0;
    Plane<uint32_t> instance;
    Plane<uint16_t> sampleCount;
    Plane<float> luminance;  // of the noisy remodulated colour
};

// One eye's visibility buffers: the latest frame's and, with gradient samples, the one before
// (the history's); they trade places each frame instead of being copied.
struct EyeVisibility {
    VisibilityBuffer buffers[2];
    int latest = 0;
    VisibilityBuffer& Latest() { return buffers[latest]; }
    const VisibilityBuffer& Latest() const { return buffers[latest]; }
    const VisibilityBuffer& Previous() const { return buffers[1 - latest]; }
};

// The merge (paper §3, "Constructing Gradient Samples"): one random
// previous-frame pixel per 3×3 stratum (one that had path samples: a drawn pixel with none passes
// the draw to the next in raster order, and a stratum with none has no gradient sample), moved to this frame with current transforms, dropped
// if off-screen or occluded in the new visibility buffer, at most one per current stratum
// (first wins, raster order of the previous strata). A survivor replaces the visibility-buffer
// entry of the pixel it lands in, with the previous seed and the previous sample count n_prev
// (the same random numbers), so its shading is both the pixel's sample of this frame and
// f_i(G→, ξ_{i−1}): no extra work, but that pixel traces n_prev instead of the spp map's
// n_cur samples. Appends the gradient samples (newLuminance filled in after shading).
void MergeGradientSamples(const EmbreeScene& embree, uint32_t runSeed, uint32_t frame, int eye,
                          const EyeCamera& camera, const EyeHistory& history, const VisibilityBuffer& prevVis,
                          FrameInputs& out, VisibilityBuffer& vis, Plane<uint8_t>& merged);

}  // namespace fovrt
