// [foveation]: one row per key of FoveationParams (defaults: its initialisers, foveation/spp_model.h)
// and the rule between keys. The config reader, ValidateFoveationParams, `fovrt config --keys` and
// the preview panel's sliders read these rows.
#include <array>
#include <limits>

#include "core/error.h"
#include "foveation/spp_model.h"

namespace fovrt {
namespace {

using F = FoveationParams;
constexpr ParamRange kSpp = Closed(1, kMaxSpp);
// The periphery's densities may go below one sample per pixel (sample masks, sample_mask.h).
constexpr ParamRange kSppMasked = Closed(kMinSpp, kMaxSpp);

// radius_deg bounds an eccentricity, the angle between two rays, which lies in [0°, 180°]:
// a radius of 180° or more would make every direction foveal (the uniform model's job), and
// every radius below it is a disc, so [0, 180).
constexpr std::array<SettingRow<FoveationParams>, 22> kFoveationRows{{
    {{.key = "foveation.model",
      .doc = "spp model: disc (thesis), linear, acuity (Guenter 2012), uniform, perceptual (the metric's CSF)",
      .names = FoveationModelNames},
     &F::model},
    {{.key = "foveation.spp_inside", .range = kSpp, .doc = "disc: spp inside the fovea disc", .slider = kSpp},
     &F::sppInside},
    {{.key = "foveation.spp_outside", .range = kSppMasked,
      .doc = "disc: spp outside it (below 1: traced on that fraction of frames)", .slider = kSppMasked},
     &F::sppOutside},
    {{.key = "foveation.radius_px", .range = OpenMin(0, 1e6),
      .doc = "disc: radius in pixels at radius_reference_width (scales with the image width)",
      .slider = Closed(10, 640)},
     &F::radiusPx},
    {{.key = "foveation.radius_reference_width", .range = Closed(1, 16384),
      .doc = "disc: the image width radius_px is given at"},
     &F::radiusReferenceWidth},
    {{.key = "foveation.radius_deg", .range = OpenMax(0, 180),
      .doc = "disc: > 0 = angular radius (eccentricity <= radius_deg) instead of radius_px"},
     &F::radiusDeg},
    {{.key = "foveation.spp_max", .range = kSpp, .doc = "linear, acuity, perceptual: spp at the gaze", .slider = kSpp},
     &F::sppMax},
    {{.key = "foveation.spp_min", .range = kSppMasked,
      .doc = "linear, acuity, perceptual: spp in the periphery (below 1: traced on that fraction of frames)",
      .slider = kSppMasked},
     &F::sppMin},
    {{.key = "foveation.foveal_deg", .range = Closed(0, 180), .doc = "linear: spp_max up to this eccentricity",
      .slider = Closed(0.5, 30)},
     &F::fovealDeg},
    {{.key = "foveation.peripheral_deg", .range = Closed(0, 180),
      .doc = "linear: spp_min from this eccentricity (> foveal_deg)", .slider = Closed(1, 90)},
     &F::peripheralDeg},
    {{.key = "foveation.omega0_deg", .range = OpenMin(0, 10), .doc = "acuity: foveal MAR ω0 in degrees (Guenter 1/48)"},
     &F::omega0Deg},
    {{.key = "foveation.mar_slope", .range = Closed(0, 10), .doc = "acuity: MAR slope m in deg/deg (Guenter 0.022)",
      .slider = Closed(0.005, 0.05)},
     &F::marSlope},
    {{.key = "foveation.noise_frequency", .range = OpenMin(0, 1),
      .doc = "perceptual: the noise's spatial frequency as a fraction of the display's Nyquist (ppd/2); "
             "1 = raw per-pixel noise, 0.5 = an octave lower, as a denoiser leaves it",
      .slider = Closed(0.1, 1)},
     &F::noiseFrequency},
    {{.key = "foveation.adapt_luminance", .range = Closed(0.01, 10000),
      .doc = "perceptual: the luminance the eye is adapted to, cd/m² (the CSF's background)"},
     &F::adaptLuminance},
    {{.key = "foveation.content_masking",
      .doc = "perceptual: fewer samples where the previous frame's texture masks noise (the metric's contrast "
             "masking of the primary-hit albedo's local contrast at the noise frequency)"},
     &F::contentMasking},
    {{.key = "foveation.noise_visibility",
      .doc = "perceptual: more samples where the eye's frames showed more visible noise (one sample's noise "
             "contrast at the display luminance, and the CSF at that luminance)"},
     &F::noiseVisibility},
    {{.key = "foveation.pooling",
      .doc = "perceptual: the visible noise it minimises: energy (n ∝ S) or the metric's own pooling (n ∝ S^1.29)",
      .names = PerceptualPoolingNames},
     &F::pooling},
    {{.key = "foveation.uniform_spp", .range = kSppMasked,
      .doc = "uniform: spp everywhere (below 1: traced on that fraction of frames)", .slider = kSppMasked},
     &F::uniformSpp},
    {{.key = "foveation.ray_budget", .range = Closed(0, double(std::numeric_limits<int64_t>::max())),
      .doc = "samples per eye per frame, the map scaled to it; 0 = none (else from spp_floor × W·H to "
              "spp_cap × W·H; uniform: to 64 × W·H)"},
     &F::rayBudget},
    {{.key = "foveation.spp_floor", .range = Closed(kMinSpp, 1),
      .doc = "ray budget: the least spp it scales a pixel to (below 1: traced on that fraction of frames)",
      .slider = Closed(kMinSpp, 1)},
     &F::sppFloor},
    {{.key = "foveation.spp_cap", .range = kSpp,
      .doc = "ray budget: the most spp it scales a pixel to (the fovea of a steep map under a large budget; not the uniform model's, at the mean)",
      .slider = kSpp},
     &F::sppCap},
    {{.key = "foveation.spp_cap_ratio", .range = Closed(0, kMaxSpp),
      .doc = "ray budget: > 0 = the cap follows the budget, this many times its mean spp (rounded up, at most "
             "64), instead of spp_cap; at least 1",
      .slider = Closed(1, 16)},
     &F::sppCapRatio},
}};
static_assert(RowsWellFormed(kFoveationRows), "a [foveation] row is malformed (see ParamRowProblem)");

}  // namespace

std::span<const SettingRow<FoveationParams>> FoveationParamTable() { return kFoveationRows; }

std::optional<ParamProblem> FoveationParamConflict(const FoveationParams& p) {
    if (p.pooling != "energy" && p.model != "perceptual")
        return ParamProblem{"foveation.pooling",
                            fmt::format("\"{}\" is read by the perceptual model only (foveation.model = \"{}\")",
                                        p.pooling, p.model)};
    if (p.contentMasking && p.model != "perceptual")
        return ParamProblem{"foveation.content_masking",
                            fmt::format("true is read by the perceptual model only (foveation.model = \"{}\")", p.model)};
    if (p.noiseVisibility && p.model != "perceptual")
        return ParamProblem{"foveation.noise_visibility",
                            fmt::format("true is read by the perceptual model only (foveation.model = \"{}\")", p.model)};
    if (p.sppCapRatio > 0.0f && p.sppCapRatio < 1.0f)
        return ParamProblem{"foveation.spp_cap_ratio",
                            fmt::format("{} would cap every pixel below the budget's mean: 0 (spp_cap decides) or "
                                        "at least 1",
                                        p.sppCapRatio)};
    if (!(p.peripheralDeg > p.fovealDeg))
        return ParamProblem{"foveation.peripheral_deg",
                            fmt::format("{} must be > foveation.foveal_deg = {}", p.peripheralDeg, p.fovealDeg)};
    return std::nullopt;
}

void ValidateFoveationParams(const FoveationParams& params) {
    ValidateRows(params, FoveationParamTable());
    if (std::optional<ParamProblem> problem = FoveationParamConflict(params))
        Fail("{}: {}", problem->key, problem->message);
}

}  // namespace fovrt
