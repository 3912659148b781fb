// What the live window can show of a frame, per eye: the denoised or noisy colour (HDR, tonemapped
// on the device), or a false-colour picture of a plane (display-referred): the spp map, albedo,
// normal, depth, the per-pixel error against a cached reference, and the running denoiser's own
// planes (Denoiser::DebugViews, e.g. A-SVGF's α, two-history's p and q).
#pragma once

#include <string>
#include <vector>

#include "core/frame_inputs.h"
#include "core/image.h"

namespace fovrt {

class Denoiser;

struct ViewImage {
    Plane<vec3> rgb;
    bool hdr = true;   // true: linear HDR colour (tonemapped for display); false: display-referred
    std::string legend;  // what the colours mean, e.g. "spp 1 (dark) .. 16 (yellow)"
};

// The views every session has, in panel order; "error" needs a cached reference.
const std::vector<std::string>& BaseViewNames();
// BaseViewNames() followed by the denoiser's debug views.
std::vector<std::string> ViewNamesFor(const Denoiser& denoiser);

struct ViewSources {
    const FrameInputs* inputs = nullptr;
    const Plane<uint16_t>* sppMap = nullptr;
    const Plane<vec3>* denoised = nullptr;
    const Plane<vec3>* reference = nullptr;  // null when no cached reference exists
    Denoiser* denoiser = nullptr;            // for its debug views
};

// Builds view `name` of one eye. Returns false (and leaves `out` unchanged) when the view does
// not exist for these sources (an unknown name, "error" without a reference).
bool BuildView(const std::string& name, const ViewSources& sources, ViewImage& out);

// Maps values in [lo, hi] through a perceptually ordered ramp (dark blue -> yellow, viridis
// samples); non-finite values show black.
vec3 FalseColour(float value, float lo, float hi);

}  // namespace fovrt
