#include "metrics/vdp_display.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include <fmt/format.h>

#include "core/error.h"
#include "metrics/filter.h"
#include "metrics/vdp_fastmath.h"

namespace fovrt {

namespace {

constexpr double kPiD = 3.14159265358979323846;
double DegToRad(double d) { return d * (kPiD / 180.0); }
double RadToDeg(double r) { return r * (180.0 / kPiD); }

// The power through VdpFastExp2/VdpFastLog2 (within 1e-6 relative of std::pow), computed on both
// sides of the select and always inlined, so that the row loop below vectorises.
[[gnu::always_inline]] inline float SrgbToLinear(float v) {
    const float power = VdpFastExp2(2.4f * VdpFastLog2((v + 0.055f) / 1.055f));
    return v > 0.04045f ? power : v / 12.92f;
}

// VdpPhotometry::Luminance over n values, one loop per EOTF so that each vectorises. A NaN (a
// renderer's stray one) shows as black; ±inf clamp to the range.
void LuminanceRow(const VdpPhotometry& photometry, const float* values, size_t n, float* out) {
    const float black = float(photometry.black), peak = float(photometry.peak);
    const float range = float(photometry.peak - photometry.black);
    // By value (std::clamp returns a reference, which keeps GCC from vectorising).
    auto finite = [](float v) { return std::isnan(v) ? 0.0f : v; };
    auto clamp = [](float v, float lo, float hi) { return v < lo ? lo : (v > hi ? hi : v); };
    switch (photometry.eotf) {
    case VdpEotf::Srgb:
        for (size_t i = 0; i < n; ++i) out[i] = range * SrgbToLinear(clamp(finite(values[i]), 0.0f, 1.0f)) + black;
        return;
    case VdpEotf::Linear:
        for (size_t i = 0; i < n; ++i) out[i] = range * clamp(finite(values[i]), 0.0f, 1.0f) + black;
        return;
    case VdpEotf::Absolute:
        for (size_t i = 0; i < n; ++i) out[i] = clamp(finite(values[i]), black, peak);
        return;
    }
}

}  // namespace

float VdpPhotometry::Luminance(float v) const {
    float out = v;
    LuminanceRow(*this, &v, 1, &out);
    return out;
}

double VdpBlackLevel(double peak, double contrast, double ambientLux, double reflectivity) {
    return peak / contrast + ambientLux / kPiD * reflectivity;
}

Plane<float> VdpLuminance(const Plane<float>& frame, const VdpPhotometry& photometry) {
    Plane<float> out(frame.width(), frame.height());
    metrics_detail::ParallelRows(frame.height(), [&](int y) {
        LuminanceRow(photometry, &frame(0, y), size_t(frame.width()), &out(0, y));
    });
    return out;
}

Plane<float> VdpLuminance(const Plane<vec3>& frame, const VdpPhotometry& photometry) {
    static_assert(sizeof(vec3) == 3 * sizeof(float), "a row of vec3 is a row of 3 floats per pixel");
    Plane<float> out(frame.width(), frame.height());
    metrics_detail::ParallelRows(frame.height(), [&](int y) {
        const size_t w = size_t(frame.width());
        std::vector<float> channels(3 * w);
        LuminanceRow(photometry, reinterpret_cast<const float*>(&frame(0, y)), 3 * w, channels.data());
        for (size_t x = 0; x < w; ++x)
            out(int(x), y) = fovrt::Luminance(vec3(channels[3 * x], channels[3 * x + 1], channels[3 * x + 2]));
    });
    return out;
}

VdpCodeLuminance::VdpCodeLuminance(const VdpPhotometry& photometry, int bits) : bits_(bits) {
    if (bits != 8 && bits != 16) Fail("VdpCodeLuminance: {}-bit codes (8 or 16 only)", bits);
    const uint32_t codes = 1u << bits, widen = 65535u / (codes - 1u);  // a code's 16-bit equal (8 bits: ·257)
    std::vector<float> values(codes);
    for (uint32_t c = 0; c < codes; ++c) values[c] = float(c * widen) / 65535.0f;  // as ReadPngRgb divides
    channel_.resize(codes);
    grey_.resize(codes);
    LuminanceRow(photometry, values.data(), codes, channel_.data());
    for (uint32_t c = 0; c < codes; ++c) grey_[c] = fovrt::Luminance(vec3(channel_[c]));
}

template <typename Code>
void VdpCodeLuminance::Image(const Code* codes, int width, int height, int channels, Plane<float>& out) const {
    static_assert(std::is_same_v<Code, uint8_t> || std::is_same_v<Code, uint16_t>);
    if (int(sizeof(Code)) * 8 != bits_ || channels < 1 || channels > 4)
        Fail("VdpCodeLuminance: a {}-bit table for {}-bit codes, {} channels", bits_, sizeof(Code) * 8, channels);
    out.ResizeForOverwrite(width, height);  // every pixel is written below
    const size_t n = out.size(), stride = size_t(channels);
    if (channels < 3) {
        for (size_t i = 0; i < n; ++i) out[i] = grey_[codes[i * stride]];
    } else {
        for (size_t i = 0; i < n; ++i) {
            const Code* c = codes + i * stride;
            out[i] = fovrt::Luminance(vec3(channel_[c[0]], channel_[c[1]], channel_[c[2]]));
        }
    }
}
template void VdpCodeLuminance::Image(const uint8_t*, int, int, int, Plane<float>&) const;
template void VdpCodeLuminance::Image(const uint16_t*, int, int, int, Plane<float>&) const;

VdpGeometry VdpGeometry::FromPixelsPerDegree(double ppd) {
    return {2.0 * std::tan(DegToRad(0.5 / ppd))};
}

VdpGeometry VdpGeometry::FromHorizontalFov(int widthPixels, double fovDegrees) {
    return {2.0 * std::tan(DegToRad(fovDegrees / 2.0)) / widthPixels};
}

VdpGeometry VdpGeometry::FromMonitor(int displayWidth, int displayHeight, double diagonalInches,
                                     double distanceMeters) {
    const double aspect = double(displayWidth) / displayHeight;
    const double heightM = std::sqrt(std::pow(diagonalInches * 25.4, 2.0) / (1.0 + aspect * aspect)) / 1000.0;
    return {aspect * heightM / displayWidth / distanceMeters};
}

double VdpGeometry::PixelsPerDegree() const {
    return 1.0 / (2.0 * RadToDeg(std::atan(0.5 * tanPerPixel)));
}

glm::dvec2 VdpGeometry::ViewDirection(double x, double y, int width, int height, int imageWidth,
                                      int imageHeight) const {
    // Pixel (x, y) of the grid lies (x − width/2)·(imageWidth/width) image pixels right of the centre.
    const double xm = (x - width / 2.0) * (double(imageWidth) * tanPerPixel / width);
    const double ym = -(y - height / 2.0) * (double(imageHeight) * tanPerPixel / height);
    return {RadToDeg(std::atan(xm)), RadToDeg(std::atan(ym))};
}

double VdpGeometry::ResolutionMagnification(double angle) const {
    // ppd(a) = ppd₀ (tan(a + δ) − tan a) / tan δ with δ half a central pixel (the reference's form),
    // evaluated as (1 + tan² a) / (1 − tan a · tan δ), the same quantity with one tan instead of
    // three and no cancellation (tan δ = tanPerPixel / 2). The metric calls it for every band pixel.
    const double t = std::tan(DegToRad(std::min(angle, 89.9)));
    return (1.0 + t * t) / (1.0 - t * (0.5 * tanPerPixel));
}

const std::vector<VdpDisplay>& VdpDisplayProfiles() {
    // Headsets: ~100 cd/m² peak and 1000:1 (the reference's standard_hmd: 100 and 0.1 cd/m²).
    static const std::vector<VdpDisplay> profiles = {
        {"headset-15", "headset, 15 pixels per degree (a 1440-wide eye at ~100° FOV), 100 cd/m²",
         {100.0, 0.1, VdpEotf::Srgb}, VdpGeometry::FromPixelsPerDegree(15.0)},
        {"headset-25", "headset, 25 pixels per degree (Quest-class), 100 cd/m²",
         {100.0, 0.1, VdpEotf::Srgb}, VdpGeometry::FromPixelsPerDegree(25.0)},
        {"headset-35", "headset, 35 pixels per degree (Varjo-class focus area), 100 cd/m²",
         {100.0, 0.1, VdpEotf::Srgb}, VdpGeometry::FromPixelsPerDegree(35.0)},
        {"monitor-24-fhd", "24-inch 1920x1080 monitor at 0.6 m, 200 cd/m², 1000:1, 250 lux office",
         {200.0, VdpBlackLevel(200.0, 1000.0, 250.0), VdpEotf::Srgb},
         VdpGeometry::FromMonitor(1920, 1080, 24.0, 0.6)},
    };
    return profiles;
}

const VdpDisplay& FindVdpDisplay(const std::string& name) {
    std::string known;
    for (const VdpDisplay& d : VdpDisplayProfiles()) {
        if (d.name == name) return d;
        known += (known.empty() ? "" : ", ") + d.name;
    }
    Fail("unknown display profile '{}' (known: {})", name, known);
}

}  // namespace fovrt
