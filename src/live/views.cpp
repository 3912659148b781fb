#include "live/views.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "denoise/denoiser.h"
#include "foveation/spp_model.h"

namespace fovrt {
namespace {

// Viridis at 0, 1/4, 1/2, 3/4, 1 (linear-light approximations of the published sRGB values).
constexpr std::array<vec3, 5> kRamp = {vec3(0.067f, 0.0f, 0.074f), vec3(0.028f, 0.047f, 0.217f),
                                       vec3(0.016f, 0.258f, 0.209f), vec3(0.126f, 0.597f, 0.069f),
                                       vec3(0.955f, 0.807f, 0.015f)};

template <typename T, typename F>
Plane<vec3> Map(const Plane<T>& plane, F f) {
    Plane<vec3> out(plane.width(), plane.height());
    for (size_t i = 0; i < plane.size(); ++i) out[i] = f(plane[i]);
    return out;
}

float FiniteMax(const Plane<float>& plane) {
    float hi = 0.0f;
    for (size_t i = 0; i < plane.size(); ++i)
        if (std::isfinite(plane[i])) hi = std::max(hi, plane[i]);
    return hi;
}

}  // namespace

vec3 FalseColour(float value, float lo, float hi) {
    if (!std::isfinite(value)) return vec3(0.0f);
    float t = hi > lo ? std::clamp((value - lo) / (hi - lo), 0.0f, 1.0f) : 0.0f;
    float x = t * float(kRamp.size() - 1);
    size_t i = std::min(size_t(x), kRamp.size() - 2);
    return glm::mix(kRamp[i], kRamp[i + 1], x - float(i));
}

const std::vector<std::string>& BaseViewNames() {
    static const std::vector<std::string> names = {"denoised", "noisy", "spp",  "albedo",
                                                   "normal",   "depth", "error", "vdp"};
    return names;
}

VdpViewStream::VdpViewStream(const RunConfig& config, const EyeCamera& camera, double fps)
    : VdpViewStream(ExperimentVdpDisplay(config, camera), config.output.exposure, fps) {}

VdpViewStream::VdpViewStream(const VdpExperimentDisplay& display, float exposureStops, double fps)
    : stream(display.geometry, fps), photometry(display.photometry), exposureStops(exposureStops) {}

Plane<float> VdpViewMap(VdpViewStream& vdp, const Plane<vec3>& test, const Plane<vec3>& reference,
                        const vec2& gazePixel) {
    return vdp.stream.Next(VdpDisplayLuminance(test, vdp.exposureStops, vdp.photometry),
                           VdpDisplayLuminance(reference, vdp.exposureStops, vdp.photometry),
                           VdpFixationAt(gazePixel));
}

std::vector<std::string> ViewNamesFor(const Denoiser& denoiser) {
    std::vector<std::string> names = BaseViewNames();
    for (const std::string& v : denoiser.DebugViews()) names.push_back(v);
    return names;
}

bool BuildView(const std::string& name, const ViewSources& s, ViewImage& out) {
    const FrameInputs& in = *s.inputs;
    if (name == "denoised") {
        out = {*s.denoised, true, "denoised colour"};
    } else if (name == "noisy") {
        out = {in.NoisyImage(), true, "noisy colour (albedo x (direct + indirect) + emission)"};
    } else if (name == "spp") {
        // Scaled to the default spp_cap so the colours hold still from frame to frame, or to the
        // map's largest where a raised cap goes past it.
        uint16_t top = uint16_t(FoveationParams{}.sppCap);
        for (size_t i = 0; i < s.sppMap->size(); ++i) top = std::max(top, (*s.sppMap)[i]);
        out = {Map(*s.sppMap, [top](uint16_t n) { return FalseColour(float(n), 1.0f, float(top)); }), false,
               fmt::format("spp map: 1 (dark) .. {} (yellow)", top)};
    } else if (name == "albedo") {
        out = {Map(in.albedo, [](const vec3& a) { return glm::clamp(a, 0.0f, 1.0f); }), false, "albedo"};
    } else if (name == "normal") {
        out = {Map(in.normal, [](const vec3& n) { return n * 0.5f + 0.5f; }), false,
               "world normal, xyz -> rgb as n/2 + 1/2"};
    } else if (name == "depth") {
        const float far = std::max(FiniteMax(in.linearDepth), 1e-3f);
        out = {Map(in.linearDepth, [far](float d) { return FalseColour(d, 0.0f, far); }), false,
               fmt::format("linear depth 0 .. {:.2f} m; background black", far)};
    } else if (name == "error") {
        if (!s.reference || s.reference->width() != s.denoised->width()) return false;
        Plane<vec3> rgb(s.denoised->width(), s.denoised->height());
        for (size_t i = 0; i < rgb.size(); ++i) {
            const vec3 d = (*s.denoised)[i] - (*s.reference)[i];
            const vec3 r = (*s.reference)[i];
            const vec3 rel = d * d / (r * r + 0.01f);  // relMSE, as the metrics (ε = 0.01)
            rgb[i] = FalseColour(std::log10((rel.r + rel.g + rel.b) / 3.0f + 1e-6f), -4.0f, 0.0f);
        }
        out = {std::move(rgb), false, "relMSE vs cached reference, log10: -4 (dark) .. 0 (yellow)"};
    } else if (name == "vdp") {
        if (!s.vdp || !s.reference || s.reference->width() != s.denoised->width()) return false;
        const Plane<float> map = VdpViewMap(*s.vdp, *s.denoised, *s.reference, s.gazePixel);
        out = {Map(map, [](float v) { return FalseColour(std::log10(v + 1e-9f), kVdpViewLog10Min, kVdpViewLog10Max); }),
               false,
               fmt::format("FovVideoVDP vs cached reference at the gaze, JOD loss per pixel, log10: {:g} (dark) .. "
                           "{:g} (yellow)", kVdpViewLog10Min, kVdpViewLog10Max)};
    } else {
        if (!s.denoiser) return false;
        const auto views = s.denoiser->DebugViews();
        if (std::find(views.begin(), views.end(), name) == views.end()) return false;
        Plane<float> plane;
        if (!s.denoiser->ReadDebugView(name, plane)) return false;
        const float hi = std::max(FiniteMax(plane), 1e-6f);
        const float top = hi <= 1.0f ? 1.0f : hi;
        out = {Map(plane, [top](float v) { return FalseColour(v, 0.0f, top); }), false,
               fmt::format("{}: 0 (dark) .. {:.3g} (yellow)", name, top)};
    }
    return true;
}

}  // namespace fovrt
