// SppModel: turns a gaze direction into a per-pixel samples-per-pixel map for one eye (SPEC §7).
// Eccentricity is the angle between a pixel's view ray and the eye's gaze ray.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "core/camera.h"
#include "core/image.h"
#include "core/setting_table.h"
#include "foveation/sample_mask.h"
#include "foveation/visible_noise.h"

namespace fovrt {

// The most samples a pixel may ask for: the renderer-to-denoiser contract's sample counts are
// uint16, and 64 lets a ray budget's fovea hold 16× a uniform 4 spp. A budget's own cap is
// BudgetSppCap: foveation.spp_cap (16 unless a design raises it), the one spp_cap_ratio gives, or
// for the uniform model at least the mean.
inline constexpr int kMaxSpp = 64;

// What the previous frames of an eye tell the perceptual model's terms (docs/foveation.md); null:
// not known (the first frame, after a cut), every pixel flat.
struct FrameFeedback {
    // The content's luminance, any scale, at the camera's resolution (the frame pipeline gives the
    // previous frame's primary-hit albedo): read by foveation.content_masking.
    const Plane<float>* content = nullptr;
    // The noise the eye's frames showed (the frame pipeline's VisibleNoiseEstimator over the frames
    // as the display shows them): read by foveation.noise_visibility.
    const VisibleNoise* noise = nullptr;
};

class SppModel {
public:
    virtual ~SppModel() = default;
    virtual std::string Name() const = 0;
    // Fills `spp` (resized to the camera's resolution) with values in [0, kMaxSpp]: a pixel whose
    // density is below 1 gets 1 on the frames its sample mask selects and 0 on the others
    // (foveation/sample_mask.h); at 1 and above it is never 0.
    // `gazeEye` is the gaze direction in this eye's space (unit, -Z forward). Only the perceptual
    // model reads `feedback`, and only with foveation.content_masking or noise_visibility.
    virtual void Generate(const EyeCamera& camera, const vec3& gazeEye, uint32_t frameIndex, Plane<uint16_t>& spp,
                          const FrameFeedback& feedback = {}) const = 0;
    // The model's continuous spp before rounding (values in [kMinSpp, kMaxSpp]); the ray-budget wrapper
    // scales it. Default: Generate() converted to float.
    virtual void GenerateDensity(const EyeCamera& camera, const vec3& gazeEye, uint32_t frameIndex,
                                 Plane<float>& density, const FrameFeedback& feedback = {}) const {
        Plane<uint16_t> spp;
        Generate(camera, gazeEye, frameIndex, spp, feedback);
        density.Resize(spp.width(), spp.height());
        for (size_t i = 0; i < spp.size(); ++i) density[i] = float(spp[i]);
    }
};

// Eccentricity in degrees: the angle between the view ray through continuous pixel `pixel` and the
// gaze ray (both in eye space). Computed with atan2 so it stays accurate near 0.
float EccentricityDegrees(const EyeCamera& camera, const vec2& pixel, const vec3& gazeEye);

// The eye's contrast sensitivity (1 / threshold contrast) to a grating of `rhoCpd` cycles per
// degree seen at `eccentricityDeg` on a background of `luminance` cd/m²: what the perceptual model
// reads. foveation/ may not include metrics/ (the same floor), so the frame pipeline passes the
// metric's own (src/pipeline/eye_sensitivity.h).
using ContrastSensitivity = std::function<double(double rhoCpd, double luminance, double eccentricityDeg)>;

// The eye's contrast masking and pooling, as the metric models them: noise of contrast c on
// content of local band contrast C is seen as D = (S·c)^p / (1 + (k·S·C)^q), S = sensitivityGain ×
// the ContrastSensitivity above, and D is pooled over pixels as Σ D^β. The perceptual model's
// content term reads the masking, its pooling = "metric" the exponents; the frame pipeline passes
// the metric's constants (src/pipeline/eye_sensitivity.h). k = 0: none given.
struct ContrastMasking {
    double sensitivityGain = 1.0;
    double k = 0.0;
    double q = 1.0;
    double p = 2.0;     // the excitation's exponent
    double beta = 1.0;  // the spatial pooling's exponent
};

// The local contrast of `luminance` in the pyramid band at `cyclesPerPixel` (a Laplacian band of
// à-trous binomial blurs, Weber contrast against the next coarser blur, its square averaged over
// the band's next scale, then the root): what masks noise of that frequency. Same size as the
// input; a pixel whose coarser blur is not positive has 0 (content_contrast.cpp).
Plane<float> LocalBandContrast(const Plane<float>& luminance, double cyclesPerPixel);

// Parameters of every model, as loaded from the [foveation] config table (defaults = thesis).
struct FoveationParams {
    std::string model = "disc";  // one of FoveationModelNames()

    // disc (thesis): sppInside within the fovea disc, sppOutside elsewhere. The radius is
    // radiusPx at an image `radiusReferenceWidth` pixels wide and scales with the image width
    // (200 px at 1280 -> 100 px at 640), so the disc covers the same angle at any resolution with
    // the same FOV. radiusDeg > 0 switches to an angular disc: eccentricity <= radiusDeg.
    // Densities below 1 (down to kMinSpp) are sample masks: spp_outside, spp_min, uniform_spp.
    int sppInside = 8;
    float sppOutside = 1.0f;
    float radiusPx = 200.0f;
    int radiusReferenceWidth = 1280;
    float radiusDeg = 0.0f;

    // linear: sppMax for e <= fovealDeg, sppMin for e >= peripheralDeg, linear in between.
    // acuity: spp = clamp(sppMax * (omega0 / (omega0 + m e))^2, sppMin, kMaxSpp) (Guenter 2012).
    int sppMax = 8;
    float sppMin = 1.0f;
    float fovealDeg = 5.0f;
    float peripheralDeg = 30.0f;
    float omega0Deg = 1.0f / 48.0f;  // foveal MAR ω0 in degrees (Guenter 2012: 1/48°)
    float marSlope = 0.022f;         // m in deg/deg (Guenter: 0.022–0.0275)

    // perceptual: spp = max(sppMax · S(e) / S(0), sppMin), S the eye's contrast sensitivity at
    // the noise's spatial frequency ρ = noiseFrequency · ppd / 2 (ppd: the camera's pixels per
    // degree, ppd / 2 its Nyquist frequency) and luminance adaptLuminance, made non-increasing in
    // e. Under a ray budget the map is n ∝ S, the allocation that minimises the visible noise
    // Σ S²/n (docs/foveation.md).
    float noiseFrequency = 0.5f;
    float adaptLuminance = 50.0f;
    // perceptual: scale each pixel's S by the masking its content gives noise, n ∝ S / √(1 + (k·S·C)^q)
    // with C the content's LocalBandContrast at the noise frequency (docs/foveation.md).
    bool contentMasking = false;
    // perceptual: the visible noise the map minimises: "energy" Σ S²/n (n ∝ S), or "metric", the
    // metric's own Σ (S·c)^(pβ) with c ∝ n^(-1/2) (n ∝ S^(2pβ/(pβ+2)), 1.29 with its p and β).
    std::string pooling = "energy";
    // perceptual: weigh each pixel by the noise its frames showed, n ∝ S(ρ, L, e) · σ/L with L the
    // display luminance and σ/L one path sample's noise contrast there (VisibleNoise), instead of
    // S(ρ, adapt_luminance, e) with σ/L the same everywhere (docs/foveation.md).
    bool noiseVisibility = false;

    // uniform: the same spp everywhere.
    float uniformSpp = 1.0f;

    // Fixed ray budget: total samples per eye per frame (0 = none). Any model's map is scaled to it,
    // each pixel kept in [sppFloor, sppCap], then dithered (at 1 and above) or masked (below 1);
    // the budget is clamped to the feasible [sppFloor*W*H, BudgetSppCap*W*H]. sppFloor = 1 traces every
    // pixel every frame.
    int64_t rayBudget = 0;
    float sppFloor = 1.0f;
    int sppCap = 16;
    // > 0: the cap follows the budget, ⌈sppCapRatio × the mean⌉ (at most kMaxSpp; BudgetSppCap), instead of
    // sppCap: the best cap measured for a steep map is about four times the mean at every budget
    // (docs/foveation-study.md), so one design can sweep budgets with it. 0 = sppCap.
    float sppCapRatio = 0.0f;

    bool operator==(const FoveationParams&) const = default;
};

// The model names (disc, linear, acuity, uniform, perceptual): the rows of the factory in models.cpp.
NameList FoveationModelNames();
// The perceptual model's poolings (energy, metric).
NameList PerceptualPoolingNames();
// [foveation]: key, member, range, meaning of every FoveationParams member (foveation_params.cpp).
std::span<const SettingRow<FoveationParams>> FoveationParamTable();
// The rule between keys (peripheral_deg > foveal_deg), for readers that add their own context.
std::optional<ParamProblem> FoveationParamConflict(const FoveationParams& params);
// Throws fovrt::Error naming the first bad foveation.* key and its range.
void ValidateFoveationParams(const FoveationParams& params);

// The key that lets the spp map hold 0 (a density below 1, traced through a sample mask), as
// "foveation.spp_outside = 0.25": the model's least density (disc: spp_outside; linear, acuity,
// perceptual: spp_min; uniform: uniform_spp) below 1, or under a ray budget spp_floor below 1 (the
// budget scales every pixel into [spp_floor, kMaxSpp], whatever the model's least). nullopt: every
// pixel is traced every frame. Read from the keys, so it says "may": a budget above W·H may keep
// every pixel at 1 or more.
std::optional<std::string> ZeroSppKey(const FoveationParams& params);
inline bool MapMayHaveZeroSamples(const FoveationParams& params) { return ZeroSppKey(params).has_value(); }

// Creates the model, wrapped when rayBudget > 0 in the ray-budget model: each map's total equals
// the budget (within a few samples, and in expectation over frames where pixels fall below 1; see
// models.cpp), each pixel's density in [sppFloor, BudgetSppCap]. Unknown model names and
// out-of-range parameters throw fovrt::Error naming the foveation.* key; so does the perceptual
// model without a `sensitivity`, and content_masking or pooling = "metric" without a `masking` (k = 0).
std::unique_ptr<SppModel> CreateSppModel(const FoveationParams& params, const ContrastSensitivity& sensitivity = {},
                                         const ContrastMasking& masking = {});
// The most spp the ray budget scales a pixel to in a W·H map: spp_cap, or with spp_cap_ratio > 0
// the ratio times the budget's mean, rounded up; for a flat map (FlatSppMap) at least the mean (it
// has no peak to bound); within [1, kMaxSpp].
int BudgetSppCap(const FoveationParams& params, int64_t pixels);
// Whether the model's map is flat (uniform): every pixel at the mean, so the cap does not bound its budget.
bool FlatSppMap(const FoveationParams& params);

}  // namespace fovrt
