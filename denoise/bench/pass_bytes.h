// Byte models of the denoiser passes (`fovrt bench --denoisers`): the bytes each timed pass reads
// and writes per pixel per frame — the sum of the plane uses of the variant's pass plan
// (denoise/pass_plan.h: derived from each pass's bindings, fills, copies and transfers), each at
// the size of its plane, so fp16 histories, combined/separate channels and plane shapes follow
// the plan.
// Assumption: every plane a dispatch binds is counted once per dispatch (the taps of a gather —
// 5×5 à-trous, 7×7 moments, bilinear reprojection, 3×3 strata — hit cache), so each figure is
// the compulsory traffic of the pass: a lower bound on the bytes it moves to and from memory.
// Per-pixel planes read only at the stratum guide pixels (A-SVGF gradient à-trous) count one
// element per stratum. The Vulkan shaders (shaders/*.comp) define what each pass reads and writes.
#pragma once

#include <string>
#include <vector>

#include "denoise/denoiser.h"
#include "denoise/params.h"
#include "denoise/pass_plan.h"

namespace fovrt {

struct PassBytes {
    std::string pass;
    double bytesPerPixel = 0.0;  // reads + writes
};

struct PassBytesOptions {
    // Fraction of pixels whose history is shorter than the variance threshold: only those run
    // the 7×7 spatial moments filter (svgf_filter_moments, indirect dispatch). 0 = steady state.
    double spatialFraction = 0.0;
    // A-SVGF gradient samples uploaded per frame, per stratum (the bench's synthetic frames carry
    // none: 0; a forward-projected frame has at most one per stratum after the claim).
    double gradientSamplesPerStratum = 1.0;
};

// svgf and svgf-weighted (params.svgf.weightBySampleCount), Vulkan pass names in recording order:
// upload, pack_guide, reproject, filter_moments, atrous<i>, modulate, download. The C++ reference
// times the same names (it has no upload/pack_guide/download).
std::vector<PassBytes> SvgfPassBytes(int width, int height, const DenoiserParams& params,
                                     const PassBytesOptions& options = {});

// Any denoiser by backend: "vulkan" gives the Vulkan pass names; "cpu" the C++ reference's timers
// (PlannedPass::referenceTimer), each the sum of the passes it spans (two-history family:
// "asvgf_gradient" = asvgf_gradient + asvgf_alpha, "atrous_blend" = Σ atrous<i> +
// two_history_blend); passes the reference runs nothing for keep their names. fovrt::Error for
// an unknown name or backend.
std::vector<PassBytes> DenoiserPassBytes(const std::string& name, const std::string& backend, int width,
                                         int height, const DenoiserParams& params,
                                         const PassBytesOptions& options = {});

// Compulsory traffic of a plan per pixel: every history read once and written once (an A/B
// pair: one read, one write), every input written (uploaded), the output written, by the planes'
// own sizes (transient ones share pool slots). A lower bound on the bytes the compute passes of
// one frame move.
double CompulsoryBytesPerPixel(const DenoiserPlan& plan, int width, int height);

}  // namespace fovrt
