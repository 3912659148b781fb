// The spp models: two-level disc, linear eccentricity falloff, acuity (MAR), uniform, perceptual
// (the eye's contrast sensitivity to noise), and the fixed-ray-budget wrapper. Densities below 1
// become sample masks (foveation/sample_mask.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "core/rng.h"
#include "foveation/spp_model.h"

namespace fovrt {

float EccentricityDegrees(const EyeCamera& camera, const vec2& pixel, const vec3& gazeEye) {
    // For unit vectors, |a - b| = 2 sin(θ/2): accurate near 0 (unlike acos of the dot product)
    // and cheaper than atan2(|a × b|, a · b).
    vec3 ray = camera.EyeDirection(pixel);
    vec3 gaze = glm::normalize(gazeEye);
    float half = std::min(0.5f * glm::length(ray - gaze), 1.0f);
    return Degrees(2.0f * std::asin(half));
}

namespace {

// The perceptual model's relative sensitivity S(e) / S(0) at one spatial frequency and luminance,
// tabulated once per map over √e ∈ [0, √180] (the CSF changes fastest near the fovea) and read
// with linear interpolation. The table is held non-increasing (a running minimum): with the
// cortical magnification alone S(ρ, e) = S(ρ / M(e), 0), which rises off-axis for a ρ below the
// CSF's peak (about 1 cpd for the metric's CSF), and the fovea sees no band worse than the
// periphery does.
class RelativeSensitivity {
public:
    static constexpr int kNodes = 97;
    static constexpr float kMaxDeg = 180.0f;

    // Relative to `normaliser`, S(ρ, L', 0) at another luminance L' (0: this row's own S(0)).
    RelativeSensitivity(const ContrastSensitivity& sensitivity, double rhoCpd, double luminance,
                        double normaliser = 0.0)
        : foveal_(normaliser > 0.0 ? normaliser : sensitivity(rhoCpd, luminance, 0.0)) {
        float least = std::numeric_limits<float>::max();
        for (int i = 0; i < kNodes; ++i) {
            const double root = std::sqrt(double(kMaxDeg)) * i / (kNodes - 1);
            const double relative = foveal_ > 0.0 ? sensitivity(rhoCpd, luminance, root * root) / foveal_ : 0.0;
            least = std::min(least, float(std::max(relative, 0.0)));
            table_[size_t(i)] = least;
        }
    }
    float At(float eccentricityDeg) const {
        const float u = std::sqrt(std::clamp(eccentricityDeg, 0.0f, kMaxDeg) / kMaxDeg) * float(kNodes - 1);
        const int i = std::min(int(u), kNodes - 2);
        const float f = u - float(i);
        return table_[size_t(i)] + f * (table_[size_t(i) + 1] - table_[size_t(i)]);
    }
    double Foveal() const { return foveal_; }  // the normaliser: S(0), absolute

private:
    double foveal_;
    std::array<float, kNodes> table_{};
};

// The noise term's sensitivity, S(ρ, L, e) / S(ρ, adapt_luminance, 0) at the display luminance L
// a pixel showed: rows of RelativeSensitivity at quarter decades from 0.01 to 10⁴ cd/m² (the
// range of adapt_luminance), read linearly in log L between rows. A row is non-increasing in e.
class LuminanceSensitivity {
public:
    static constexpr int kRows = 25;
    static constexpr double kLogMin = -2.0, kLogStep = 0.25;

    LuminanceSensitivity(const ContrastSensitivity& sensitivity, double rhoCpd, double adaptFoveal) {
        rows_.reserve(kRows);
        for (int i = 0; i < kRows; ++i)
            rows_.emplace_back(sensitivity, rhoCpd, std::pow(10.0, kLogMin + kLogStep * i), adaptFoveal);
    }
    float At(float luminance, float eccentricityDeg) const {
        const double u = std::clamp((std::log10(std::max(double(luminance), 1e-30)) - kLogMin) / kLogStep, 0.0,
                                    double(kRows - 1));
        const int i = std::min(int(u), kRows - 2);
        const float f = float(u - i);
        const float lo = rows_[size_t(i)].At(eccentricityDeg), hi = rows_[size_t(i) + 1].At(eccentricityDeg);
        return lo + f * (hi - lo);
    }

private:
    std::vector<RelativeSensitivity> rows_;
};

// The perceptual model's exponents: minimising the visible noise Σ S^a M^-b n^(-a/2) (a = pβ, b = β:
// the excitation's and the pooling's exponents, p = 2 and β = 1 for the noise energy) under
// Σ n = B gives n ∝ S^(2a/(a+2)) · M^(-2b/(a+2)) (docs/foveation.md).
struct PoolingExponents {
    float sensitivity = 1.0f;  // 2a/(a+2)
    float masking = 0.5f;      // 2b/(a+2)
    static PoolingExponents Of(double p, double beta) {
        const double a = p * beta;
        return {float(2.0 * a / (a + 2.0)), float(2.0 * beta / (a + 2.0))};
    }
};

// The content term of the perceptual model: the content's local band contrast C per pixel and
// the metric's masking constants with S(0) folded in, so that the masking signal at eccentricity
// e is kS0 · S(e)/S(0) · C.
struct ContentMasking {
    Plane<float> contrast;
    float kS0 = 0.0f;
    float q = 1.0f;
    float exponent = 0.5f;  // PoolingExponents::masking
    // (1 + (k·S·C)^q)^-exponent: the factor by which masking lowers the optimal density.
    float Factor(int x, int y, float relativeSensitivity) const {
        const float signal = kS0 * relativeSensitivity * contrast(x, y);
        return std::pow(1.0f + std::pow(signal, q), -exponent);
    }
};

// Per-call gaze data shared by all pixels of one map.
struct GazeContext {
    vec3 gaze;       // unit, eye space
    bool inFront;    // gaze points into the image half-space (always, for real gaze)
    vec2 gazePixel;  // continuous pixel of the gaze ray (valid when inFront)
    const RelativeSensitivity* sensitivity = nullptr;  // the perceptual model's, else none
    const ContentMasking* masking = nullptr;           // its content term, else none (flat content)
    float sensitivityExponent = 1.0f;                  // its PoolingExponents::sensitivity
    // Its noise term, else none (σ/L the same everywhere, the CSF at adapt_luminance), and what
    // divides S·σ/L so that the most visible noise gets spp_max (the bounds then clip nothing the
    // budget would scale back).
    const VisibleNoise* noise = nullptr;
    const LuminanceSensitivity* luminanceSensitivity = nullptr;
    float noiseNormaliser = 1.0f;
};

// A model's continuous spp at one pixel; `e` is the pixel's eccentricity (EccentricityDegrees).
using DensityFn = float (*)(const FoveationParams& p, const EyeCamera& camera, const vec2& pixel, float e,
                            const GazeContext& g);

// disc: sppInside within the fovea disc (in pixels, or in degrees when radiusDeg > 0).
float DiscDensity(const FoveationParams& p, const EyeCamera& camera, const vec2& pixel, float e, const GazeContext& g) {
    bool inside;
    if (p.radiusDeg > 0.0f) {
        inside = e <= p.radiusDeg;
    } else {
        // Gaze behind the eye (never for real gaze): no pixel is foveal.
        float radius = p.radiusPx * float(camera.width()) / float(p.radiusReferenceWidth);
        vec2 d = pixel - g.gazePixel;
        inside = g.inFront && glm::dot(d, d) <= radius * radius;
    }
    return inside ? float(p.sppInside) : p.sppOutside;
}

float LinearDensity(const FoveationParams& p, const EyeCamera&, const vec2&, float e, const GazeContext&) {
    if (e <= p.fovealDeg) return float(p.sppMax);
    if (e >= p.peripheralDeg) return p.sppMin;
    float t = (e - p.fovealDeg) / (p.peripheralDeg - p.fovealDeg);
    return float(p.sppMax) + t * (p.sppMin - float(p.sppMax));
}

float AcuityDensity(const FoveationParams& p, const EyeCamera&, const vec2&, float e, const GazeContext&) {
    float ratio = p.omega0Deg / (p.omega0Deg + p.marSlope * e);  // ω0 / ω(e)
    return std::max(p.sppMin, float(p.sppMax) * ratio * ratio);
}

float UniformDensity(const FoveationParams& p, const EyeCamera&, const vec2&, float, const GazeContext&) {
    return p.uniformSpp;
}

float PerceptualDensity(const FoveationParams& p, const EyeCamera&, const vec2& pixel, float e, const GazeContext& g) {
    // The noise term: the CSF at the luminance the pixel showed, and its noise contrast.
    const float relative = g.noise ? g.luminanceSensitivity->At(g.noise->LuminanceAt(pixel.x, pixel.y), e)
                                   : g.sensitivity->At(e);
    const float noise = g.noise ? g.noise->ContrastAt(pixel.x, pixel.y) / g.noiseNormaliser : 1.0f;
    const float masked = g.masking ? g.masking->Factor(int(pixel.x), int(pixel.y), relative) : 1.0f;
    const float seen = relative * noise;
    const float weight = g.sensitivityExponent == 1.0f ? seen : std::pow(seen, g.sensitivityExponent);
    return std::max(p.sppMin, float(p.sppMax) * weight * masked);
}

// The models by name: the one list of foveation.model's values. `leastKey`, `least`: the key and
// member of the density's least value (no pixel's density lies below it; ZeroSppKey reads them).
// `readsSensitivity`: the density reads the eye's contrast sensitivity (GazeContext::sensitivity).
struct ModelRow {
    const char* name;
    DensityFn density;
    const char* leastKey;
    float FoveationParams::*least;
    bool readsSensitivity = false;
    bool flat = false;  // every pixel at the same density: no peak for a budget's cap to bound
};
constexpr std::array<ModelRow, 5> kModels{{
    {"disc", DiscDensity, "foveation.spp_outside", &FoveationParams::sppOutside},
    {"linear", LinearDensity, "foveation.spp_min", &FoveationParams::sppMin},
    {"acuity", AcuityDensity, "foveation.spp_min", &FoveationParams::sppMin},
    {"uniform", UniformDensity, "foveation.uniform_spp", &FoveationParams::uniformSpp, false, true},
    {"perceptual", PerceptualDensity, "foveation.spp_min", &FoveationParams::sppMin, true},
}};
constexpr std::array<const char*, kModels.size()> kModelNames = [] {
    std::array<const char*, kModels.size()> names{};
    for (size_t i = 0; i < kModels.size(); ++i) names[i] = kModels[i].name;
    return names;
}();

// The map's value at pixel (x, y) for a density below 1: its sample mask's bit for this frame.
uint16_t MaskedSpp(float density, int x, int y, uint32_t frameIndex) {
    return SampleMaskSelects(density, x, y, frameIndex) ? 1 : 0;
}

// A model defined by a continuous spp per pixel (its row's density); Generate() rounds to nearest
// and clamps at 1 and above, and masks below 1.
class DensityModel final : public SppModel {
public:
    DensityModel(const ModelRow& row, const FoveationParams& p, ContrastSensitivity sensitivity,
                 const ContrastMasking& masking)
        : row_(row), p_(p), sensitivity_(std::move(sensitivity)), masking_(masking) {}
    std::string Name() const override { return row_.name; }

    void Generate(const EyeCamera& camera, const vec3& gazeEye, uint32_t frameIndex, Plane<uint16_t>& spp,
                  const FrameFeedback& feedback) const override {
        Plane<float> density;
        GenerateDensity(camera, gazeEye, frameIndex, density, feedback);
        spp.Resize(density.width(), density.height());
        for (int y = 0; y < spp.height(); ++y)
            for (int x = 0; x < spp.width(); ++x) {
                const float d = density(x, y);
                spp(x, y) = d < 1.0f ? MaskedSpp(d, x, y, frameIndex)
                                     : uint16_t(std::clamp(std::lround(d), 1L, long(kMaxSpp)));
            }
    }
    void GenerateDensity(const EyeCamera& camera, const vec3& gazeEye, uint32_t, Plane<float>& density,
                         const FrameFeedback& feedback) const override {
        const int w = camera.width(), h = camera.height();
        density.Resize(w, h);
        GazeContext g;
        g.gaze = glm::normalize(gazeEye);
        g.inFront = g.gaze.z < -1e-6f;
        g.gazePixel = g.inFront ? camera.PixelOfEyeDirection(g.gaze) : vec2(0.0f);
        std::optional<RelativeSensitivity> relative;
        if (row_.readsSensitivity) {
            const double rho = double(p_.noiseFrequency) * 0.5 * double(camera.PixelsPerDegree());
            g.sensitivity = &relative.emplace(sensitivity_, rho, double(p_.adaptLuminance));
        }
        const PoolingExponents exponents =
            p_.pooling == "metric" ? PoolingExponents::Of(masking_.p, masking_.beta) : PoolingExponents{};
        g.sensitivityExponent = exponents.sensitivity;
        std::optional<ContentMasking> masking;
        const Plane<float>* content = feedback.content;
        if (p_.contentMasking && content) {
            if (content->width() != w || content->height() != h)
                Fail("foveation.content_masking: the content is {}x{}, the eye's image {}x{}", content->width(),
                     content->height(), w, h);
            // The band at the noise's frequency: noise_frequency of Nyquist, in cycles per pixel.
            masking.emplace(ContentMasking{LocalBandContrast(*content, 0.5 * double(p_.noiseFrequency)),
                                           float(masking_.k * masking_.sensitivityGain * relative->Foveal()),
                                           float(masking_.q), exponents.masking});
            g.masking = &*masking;
        }
        std::optional<LuminanceSensitivity> luminanceSensitivity;
        if (p_.noiseVisibility && feedback.noise && feedback.noise->Valid()) {
            if (!feedback.noise->Matches(w, h))
                Fail("foveation.noise_visibility: the noise was estimated on a {}x{} image, the eye's is {}x{}",
                     feedback.noise->imageWidth, feedback.noise->imageHeight, w, h);
            g.luminanceSensitivity = &luminanceSensitivity.emplace(
                sensitivity_, double(p_.noiseFrequency) * 0.5 * double(camera.PixelsPerDegree()), relative->Foveal());
            g.noise = feedback.noise;
            // The most visible noise: the largest contrast times the largest foveal sensitivity
            // over the tiles (a bound on S·σ/L anywhere: S falls with e, and the tiles'
            // interpolants lie between their values).
            float contrast = 0.0f, sensitivity = 0.0f;
            for (size_t i = 0; i < g.noise->contrast.size(); ++i) {
                contrast = std::max(contrast, g.noise->contrast[i]);
                sensitivity = std::max(sensitivity, g.luminanceSensitivity->At(g.noise->luminance[i], 0.0f));
            }
            g.noiseNormaliser = std::max(contrast * sensitivity, 1e-30f);
        }
        // View rays are separable in tangent space: (tx[x], ty[y], -1), normalised per pixel.
        std::vector<float> tx(static_cast<size_t>(w)), ty(static_cast<size_t>(h));
        for (int x = 0; x < w; ++x) {
            vec3 d = camera.EyeDirection(vec2(x + 0.5f, 0.5f));
            tx[size_t(x)] = d.x / -d.z;
        }
        for (int y = 0; y < h; ++y) {
            vec3 d = camera.EyeDirection(vec2(0.5f, y + 0.5f));
            ty[size_t(y)] = d.y / -d.z;
        }
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                vec3 ray = vec3(tx[size_t(x)], ty[size_t(y)], -1.0f);
                ray *= 1.0f / std::sqrt(glm::dot(ray, ray));
                // Same formula as EccentricityDegrees (2·asin(|ray − gaze| / 2)).
                float e = Degrees(2.0f * std::asin(std::min(0.5f * glm::length(ray - g.gaze), 1.0f)));
                density(x, y) = std::clamp(row_.density(p_, camera, vec2(x + 0.5f, y + 0.5f), e, g), kMinSpp,
                                           float(kMaxSpp));
            }
        }
    }

private:
    ModelRow row_;
    FoveationParams p_;
    ContrastSensitivity sensitivity_;
    ContrastMasking masking_;
};

// Fixed ray budget: scale the inner model's continuous map by s so that
// Σ clamp(s·d, floor, cap) = budget (regula falsi; the sum is monotone in s), then round the
// targets at 1 and above with serpentine 1-D error diffusion and mask those below 1. Every
// diffused target lies in [1, cap] and the carried error in [-0.5, 0.5], so each output stays
// in [1, cap] and their total differs from their targets' by < 1 sample; a masked pixel of
// target d is traced d times per frame on average (sample_mask.h), so the map's total meets the
// budget in expectation, within that sample plus the solver tolerance (0.05) and float rounding
// of the targets. The carry starts at a hash of the frame index, so the dither pattern changes
// from frame to frame deterministically.
class BudgetModel final : public SppModel {
public:
    // The budget's keys of `p` (ray_budget, spp_floor, spp_cap, spp_cap_ratio); the cap is resolved
    // per map, as it may follow the budget's mean over the map's pixels.
    BudgetModel(std::unique_ptr<SppModel> inner, const FoveationParams& p)
        : inner_(std::move(inner)), keys_(p) {}
    std::string Name() const override { return "budget(" + inner_->Name() + ")"; }

    void GenerateDensity(const EyeCamera& camera, const vec3& gazeEye, uint32_t frameIndex, Plane<float>& density,
                         const FrameFeedback& feedback) const override {
        inner_->GenerateDensity(camera, gazeEye, frameIndex, density, feedback);
        const int capSpp = BudgetSppCap(keys_, int64_t(density.size()));
        const double n = double(density.size()), floor = double(keys_.sppFloor), cap = double(capSpp);
        const double target = std::clamp(double(keys_.rayBudget), n * floor, n * cap);
        float dMin = float(capSpp);
        for (size_t i = 0; i < density.size(); ++i) {
            dMin = std::min(dMin, density[i]);
        }
        dMin = std::max(dMin, 1e-6f);
        auto total = [&](double s) {
            double sum = 0.0;
            for (size_t i = 0; i < density.size(); ++i)
                sum += std::clamp(s * double(density[i]), floor, cap);
            return sum;
        };
        // total(0) = n·floor <= target <= total(cap / dMin) = n·cap; total is monotone and
        // piecewise linear in s, so regula falsi (Illinois variant) converges in a few passes.
        double lo = 0.0, hi = cap / dMin;
        double fLo = n * floor - target, fHi = n * cap - target;
        double s = hi;
        int side = 0;
        for (int it = 0; it < 100 && fHi - fLo > 0.0 && hi - lo > 1e-12 * hi; ++it) {
            s = (lo * fHi - hi * fLo) / (fHi - fLo);
            double f = total(s) - target;
            if (std::abs(f) <= 0.05) break;
            if (f < 0) {
                lo = s, fLo = f;
                if (side == -1) fHi *= 0.5;
                side = -1;
            } else {
                hi = s, fHi = f;
                if (side == 1) fLo *= 0.5;
                side = 1;
            }
        }
        for (size_t i = 0; i < density.size(); ++i)
            density[i] = float(std::clamp(s * double(density[i]), floor, cap));
    }

    void Generate(const EyeCamera& camera, const vec3& gazeEye, uint32_t frameIndex, Plane<uint16_t>& spp,
                  const FrameFeedback& feedback) const override {
        Plane<float> density;
        GenerateDensity(camera, gazeEye, frameIndex, density, feedback);
        spp.Resize(density.width(), density.height());
        const double cap = double(BudgetSppCap(keys_, int64_t(density.size())));
        double carry = double(HashPcg(frameIndex ^ 0x5bd1e995u)) / 4294967296.0 - 0.5;
        for (int y = 0; y < spp.height(); ++y) {
            for (int i = 0; i < spp.width(); ++i) {
                int x = (y % 2 == 0) ? i : spp.width() - 1 - i;  // serpentine
                if (density(x, y) < 1.0f) {
                    spp(x, y) = MaskedSpp(density(x, y), x, y, frameIndex);
                    continue;
                }
                double want = double(density(x, y)) + carry;
                double value = std::clamp(std::floor(want + 0.5), 1.0, cap);
                carry = want - value;
                spp(x, y) = uint16_t(value);
            }
        }
    }

private:
    std::unique_ptr<SppModel> inner_;
    FoveationParams keys_;
};

}  // namespace

NameList FoveationModelNames() { return kModelNames; }

NameList PerceptualPoolingNames() {
    static constexpr std::array<const char*, 2> kNames = {"energy", "metric"};
    return kNames;
}

std::optional<std::string> ZeroSppKey(const FoveationParams& p) {
    // Under a ray budget every pixel is scaled into [spp_floor, spp_cap], whatever the model's least.
    if (p.rayBudget > 0)
        return p.sppFloor < 1.0f ? std::optional(fmt::format("foveation.spp_floor = {}", p.sppFloor)) : std::nullopt;
    for (const ModelRow& row : kModels)
        if (p.model == row.name && p.*row.least < 1.0f) return fmt::format("{} = {}", row.leastKey, p.*row.least);
    return std::nullopt;
}

std::unique_ptr<SppModel> CreateSppModel(const FoveationParams& p, const ContrastSensitivity& sensitivity,
                                         const ContrastMasking& masking) {
    ValidateFoveationParams(p);
    std::unique_ptr<SppModel> model;
    for (const ModelRow& row : kModels) {
        if (p.model != row.name) continue;
        if (row.readsSensitivity && !sensitivity)
            Fail("foveation.model = \"{}\" reads the eye's contrast sensitivity, and none was given "
                 "(the frame pipeline gives the metric's)", row.name);
        if ((p.contentMasking || p.pooling == "metric") && !(masking.k > 0.0))
            Fail("{} reads the eye's contrast masking and pooling, and none was given (the frame pipeline gives "
                 "the metric's)",
                 p.contentMasking ? "foveation.content_masking" : "foveation.pooling = \"metric\"");
        model = std::make_unique<DensityModel>(row, p, sensitivity, masking);
    }
    if (p.rayBudget > 0) model = std::make_unique<BudgetModel>(std::move(model), p);
    return model;
}

bool FlatSppMap(const FoveationParams& p) {
    return std::ranges::any_of(kModels, [&](const ModelRow& row) { return p.model == row.name && row.flat; });
}

int BudgetSppCap(const FoveationParams& p, int64_t pixels) {
    if (pixels <= 0) return p.sppCap;
    // A budget set from a mean spp is that mean times W·H rounded to whole samples, up to half a
    // sample above it, which must not raise the cap by one.
    const double mean = (double(p.rayBudget) - 0.5) / double(pixels);
    double cap = p.sppCapRatio > 0.0f ? std::ceil(double(p.sppCapRatio) * mean) : double(p.sppCap);
    // The cap bounds a shaped map's peak; a uniform map has none, every pixel at the mean, so its
    // budget is feasible up to kMaxSpp whatever the cap (uniform sampling at 32 spp as a sweep's anchor).
    if (FlatSppMap(p)) cap = std::max(cap, std::ceil(mean));
    return int(std::clamp(cap, 1.0, double(kMaxSpp)));
}

}  // namespace fovrt
