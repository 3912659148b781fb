// What the live window can show of a frame, per eye: the denoised or noisy colour (HDR, tonemapped
// on the device), or a false-colour picture of a plane (display-referred): the spp map, albedo,
// normal, depth, the per-pixel error against a cached reference (relMSE: "error"; FovVideoVDP's
// difference map, foveated at the gaze, its temporal channels kept across frames: "vdp"), and the
// running denoiser's own planes (Denoiser::DebugViews, e.g. A-SVGF's α, two-history's p and q).
#pragma once

#include <string>
#include <vector>

#include "pipeline/metric_display.h"
#include "config/config.h"
#include "core/camera.h"
#include "core/frame_inputs.h"
#include "core/image.h"
#include "metrics/vdp_stream.h"

namespace fovrt {

class Denoiser;

struct ViewImage {
    Plane<vec3> rgb;
    bool hdr = true;   // true: linear HDR colour (tonemapped for display); false: display-referred
    std::string legend;  // what the colours mean, e.g. "spp 1 (dark) .. 16 (yellow)"
};

// The views every session has, in panel order; "error" and "vdp" need a cached reference.
const std::vector<std::string>& BaseViewNames();
// BaseViewNames() followed by the denoiser's debug views.
std::vector<std::string> ViewNamesFor(const Denoiser& denoiser);

// The "vdp" view's state for one eye: FovVideoVDP on the experiment's display for this eye camera
// (pipeline/metric_display.h: metric.* keys, the PNGs' exposure), its temporal channels across frames.
// The owner resets it when the frames stop being one sequence (another view or denoiser, a cut).
struct VdpViewStream {
    VdpViewStream(const RunConfig& config, const EyeCamera& camera, double fps);
    VdpViewStream(const VdpExperimentDisplay& display, float exposureStops, double fps);
    VdpStream stream;
    VdpPhotometry photometry;
    float exposureStops = 0.0f;
};

// The stream's difference map (JOD lost per pixel) of `test` against `reference`, foveated at
// `gazePixel` (continuous pixel coordinates, as EyeFrame::trueGazePixel).
Plane<float> VdpViewMap(VdpViewStream& vdp, const Plane<vec3>& test, const Plane<vec3>& reference,
                        const vec2& gazePixel);
// The view's colour scale: log10 of the JOD loss per pixel over [kVdpViewLog10Min, kVdpViewLog10Max].
inline constexpr float kVdpViewLog10Min = -3.0f;
inline constexpr float kVdpViewLog10Max = 1.0f;

struct ViewSources {
    const FrameInputs* inputs = nullptr;
    const Plane<uint16_t>* sppMap = nullptr;
    const Plane<vec3>* denoised = nullptr;
    const Plane<vec3>* reference = nullptr;  // null when no cached reference exists
    Denoiser* denoiser = nullptr;            // for its debug views
    VdpViewStream* vdp = nullptr;            // the eye's "vdp" stream (null: no such view)
    vec2 gazePixel{0.0f};                    // where the eye looks (the "vdp" view's fixation)
};

// Builds view `name` of one eye. Returns false (and leaves `out` unchanged) when the view does
// not exist for these sources (an unknown name, "error" or "vdp" without a reference).
bool BuildView(const std::string& name, const ViewSources& sources, ViewImage& out);

// Maps values in [lo, hi] through a perceptually ordered ramp (dark blue -> yellow, viridis
// samples); non-finite values show black.
vec3 FalseColour(float value, float lo, float hi);

}  // namespace fovrt
