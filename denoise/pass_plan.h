// The pass plan of a denoiser variant: the ordered passes one frame runs (the names the Vulkan
// hosts time) and, for each, the planes of the memory plan it reads and writes. Built in one
// place from the variant row, the parameters and the size; the byte model of `fovrt bench`
// (denoise/bench/pass_bytes.h) is the sum of its uses, and a test holds it to the memory plan:
// every plane a pass uses is allocated, and every allocated plane is used.
//
// Counting convention (the byte model's): every plane a dispatch binds counts once per dispatch,
// whatever its gather footprint (5×5 à-trous, 7×7 moments, bilinear taps hit cache), so a pass's
// sum is its compulsory traffic: a lower bound on the bytes it moves.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "denoise/denoiser.h"
#include "denoise/params.h"

namespace fovrt {

// Which part of a plane a use touches, resolved when the bytes are counted (PassBytesOptions).
enum class Coverage {
    EveryPixel,          // the whole plane
    ListedPixels,        // the pixels on the spatial-variance list (svgf_filter_moments' indirect
                         // dispatch)
    StratumGuidePixels,  // one pixel per 3×3 stratum (A-SVGF's gather of the stratum guide)
    ClaimedStrata,       // strata that received a gradient sample
    UploadedSamples,     // the uploaded share of the gradient-sample capacity (two per stratum)
};

enum class Access { Read, Write };

struct PlaneUse {
    std::string plane;  // memory-plan buffer name without its ".A"/".B" history side
    Access access = Access::Read;
    double times =
        1.0;  // whole-plane transfers: 2 for an upload (staging read + device write) or a copy
    Coverage coverage = Coverage::EveryPixel;
    // > 0: bytes per pixel of a binding the shader loads whatever is bound (a placeholder plane).
    double fixedBytesPerPixel = 0.0;
};

struct PlannedPass {
    std::string name;  // the timer name: "reproject", "atrous0", …
    std::vector<PlaneUse> uses;
};

struct DenoiserPlan {
    std::vector<BufferPlan> buffers;  // the memory plan (PlanDenoiserMemory)
    std::vector<PlannedPass> passes;  // Vulkan recording order
};

// The plan of the named variant (DenoiserVariants()) at W×H for one eye. fovrt::Error for an
// unknown name or size.
DenoiserPlan BuildDenoiserPlan(std::string_view variant, const DenoiserParams& params, int width,
                               int height);

}  // namespace fovrt
