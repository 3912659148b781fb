// The golden cases of FovVideoVDP (src/metrics/fovvideovdp.h) and the closed-form inputs they
// are computed on, shared by the metric's test and the `fovrt vdp` command's test.
//
// Golden values: produced by the reference implementation gfxdisp/FovVideoVDP at commit
// 31254d0419f697a8415a191b71b4d8364d4f0843 (pyfvvdp, parameters v1.2.3, CPU PyTorch 1.13 under
// Debian's python3-torch, float32 inputs), run outside this repository by a generator script that
// builds the inputs below with numpy and calls fvvdp.predict(test, reference, dim_order "HW" or
// "FHW", frames_per_second, fixation_point). Each case below is re-created here sample for sample:
//   reference frame  v(x, y, f) = 0.45 + 0.2 sin(2π X/13) cos(2π y/9) ± 0.15 (16-px checker),
//                    X = x + vx·f (content moving vx px/frame);
//   noise            amplitude · (PCG hash of (seed, frame, x, y) / 2³² − 0.5), NoiseAt below;
//   blur             [1 2 1]/4 separable blur, edges clamped, applied twice;
//   flicker          + amplitude · cos(2π hz f / fps) inside a box;
//   then clamped to [0, 1] (display-encoded, sRGB EOTF, peak/contrast as listed).
//   HDR cases: reference L = 10^(5v − 1) cd/m², test L·(1 + 0.4 noise), absolute photometry
//   (fvvdp_display_photo_absolute, 0.005–10000 cd/m²).
// Geometry is always the image's own (see vdp_display.h): "ppd N" = fvvdp_display_geometry with
// the image's resolution and fov_horizontal = 2 atan(W tan(0.5°/N)); "monitor d in at m" =
// diagonal_size_inches d (of the image itself) at distance_m m. Fixations are the reference's
// fixation_point (it adds 0.5 px), per frame when moving.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "metrics/fovvideovdp.h"

namespace fovrt::vdp_test {

inline constexpr double kPiD = 3.14159265358979323846;

inline uint32_t Pcg(uint32_t v) {
    v = v * 747796405u + 2891336453u;
    const uint32_t w = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
    return (w >> 22u) ^ w;
}

inline double NoiseAt(int seed, int frame, int x, int y) {
    const uint32_t key = (uint32_t(seed) * 73856093u) ^ (uint32_t(frame) * 19349663u) ^ (uint32_t(y) * 83492791u) ^ uint32_t(x);
    return double(Pcg(key)) / 4294967296.0 - 0.5;
}

inline std::vector<double> Pattern(int w, int h, int frame, double vx) {
    std::vector<double> v(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double X = x + vx * frame;
            const double checker = std::fmod(std::floor(X / 16) + std::floor(y / 16.0), 2.0) == 0 ? 1.0 : -1.0;
            v[size_t(y) * size_t(w) + size_t(x)] =
                0.45 + 0.2 * std::sin(2 * kPiD * X / 13.0) * std::cos(2 * kPiD * y / 9.0) + 0.15 * checker;
        }
    return v;
}

inline std::vector<double> Blur(const std::vector<double>& in, int w, int h) {
    auto at = [&](const std::vector<double>& s, int x, int y) {
        return s[size_t(std::clamp(y, 0, h - 1)) * size_t(w) + size_t(std::clamp(x, 0, w - 1))];
    };
    std::vector<double> tmp(in.size()), out(in.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            tmp[size_t(y) * size_t(w) + size_t(x)] = (at(in, x - 1, y) + 2 * at(in, x, y) + at(in, x + 1, y)) / 4;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            out[size_t(y) * size_t(w) + size_t(x)] = (at(tmp, x, y - 1) + 2 * at(tmp, x, y) + at(tmp, x, y + 1)) / 4;
    return out;
}

enum class Geo { Ppd, Monitor };
enum class Fix { None, Fixed, Path };

struct GoldenCase {
    const char* name;
    int w = 160, h = 90, frames = 1;
    double fps = 0;
    int seed = 0;
    double noise = 0;
    bool blur = false, hdr = false;
    double flickerHz = 0, flickerAmp = 0;
    int box[4] = {0, 0, 0, 0};  // x0, y0, x1, y1; all zero = whole frame
    double vx = 0;
    Geo geo = Geo::Ppd;
    double ppd = 20, diagonalInches = 0, distance = 0;
    double peak = 100, contrast = 1000;
    bool foveated = false;
    Fix fix = Fix::None;
    float fx0 = 0, fy0 = 0, fx1 = 0, fy1 = 0;
    double jod = 0;  // the reference's
};

// Display-encoded (or cd/m² for HDR) test and reference frames of a case, as float32.
struct Frames {
    std::vector<Plane<float>> test, reference;
};

inline Frames MakeFrames(const GoldenCase& c) {
    Frames out;
    for (int f = 0; f < c.frames; ++f) {
        std::vector<double> ref = Pattern(c.w, c.h, f, c.vx), test;
        if (c.hdr) {
            for (double& v : ref) v = std::pow(10.0, 5 * v - 1);
            test = ref;
            for (int y = 0; y < c.h; ++y)
                for (int x = 0; x < c.w; ++x) test[size_t(y * c.w + x)] *= 1 + 0.4 * NoiseAt(c.seed, f, x, y);
        } else {
            test = c.blur ? Blur(Blur(ref, c.w, c.h), c.w, c.h) : ref;
            for (int y = 0; y < c.h; ++y)
                for (int x = 0; x < c.w; ++x) {
                    double& v = test[size_t(y * c.w + x)];
                    if (c.noise != 0) v += c.noise * NoiseAt(c.seed, f, x, y);
                    const bool whole = c.box[2] == 0;
                    if (c.flickerHz != 0 && (whole || (x >= c.box[0] && x < c.box[2] && y >= c.box[1] && y < c.box[3])))
                        v += c.flickerAmp * std::cos(2 * kPiD * c.flickerHz * f / c.fps);
                    v = std::clamp(v, 0.0, 1.0);
                }
        }
        Plane<float> t(c.w, c.h), r(c.w, c.h);
        for (size_t i = 0; i < t.size(); ++i) t[i] = float(test[i]), r[i] = float(ref[i]);
        out.test.push_back(std::move(t));
        out.reference.push_back(std::move(r));
    }
    return out;
}

inline VdpPhotometry PhotometryOf(const GoldenCase& c) {
    if (c.hdr) return {10000.0, 0.005, VdpEotf::Absolute};
    return {c.peak, VdpBlackLevel(c.peak, c.contrast), VdpEotf::Srgb};
}

inline VdpGeometry GeometryOf(const GoldenCase& c) {
    return c.geo == Geo::Ppd ? VdpGeometry::FromPixelsPerDegree(c.ppd)
                             : VdpGeometry::FromMonitor(c.w, c.h, c.diagonalInches, c.distance);
}

inline VdpOptions OptionsOf(const GoldenCase& c) {
    VdpOptions o;
    o.foveated = c.foveated;
    if (c.fix == Fix::Fixed) o.fixations = {{c.fx0, c.fy0}};
    if (c.fix == Fix::Path)
        for (int f = 0; f < c.frames; ++f)
            o.fixations.push_back({float(c.fx0 + (c.fx1 - c.fx0) * f / double(c.frames - 1)),
                                   float(c.fy0 + (c.fy1 - c.fy0) * f / double(c.frames - 1))});
    return o;
}

inline VdpResult ScoreCase(const GoldenCase& c, bool diffMaps = false) {
    const Frames frames = MakeFrames(c);
    const VdpPhotometry photometry = PhotometryOf(c);
    std::vector<Plane<float>> test, reference;
    for (const Plane<float>& p : frames.test) test.push_back(VdpLuminance(p, photometry));
    for (const Plane<float>& p : frames.reference) reference.push_back(VdpLuminance(p, photometry));
    VdpOptions options = OptionsOf(c);
    options.diffMaps = diffMaps;
    return FovVideoVdp(GeometryOf(c)).Score(test, reference, c.fps, options);
}

// The cases of the generator, with the reference's JOD.
inline const std::vector<GoldenCase>& GoldenCases() {
    static const std::vector<GoldenCase> cases = [] {
        std::vector<GoldenCase> v;
        v.push_back({.name = "still, noise, 20 ppd", .seed = 1, .noise = 0.06, .jod = 9.579300});
        v.push_back({.name = "still, noise, 20 ppd, foveated at the centre", .seed = 1, .noise = 0.06,
                     .foveated = true, .jod = 9.684002});
        v.push_back({.name = "still, noise, 20 ppd, foveated near a corner", .seed = 1, .noise = 0.06,
                     .foveated = true, .fix = Fix::Fixed, .fx0 = 10, .fy0 = 12, .jod = 9.719761});
        v.push_back({.name = "still, blur, 20 ppd", .blur = true, .jod = 8.067183});
        v.push_back({.name = "still, blur, 2-inch monitor at 0.6 m (37.8 ppd), foveated", .blur = true,
                     .geo = Geo::Monitor, .diagonalInches = 2.0, .distance = 0.6, .foveated = true,
                     .fix = Fix::Fixed, .fx0 = 120, .fy0 = 30, .jod = 8.943862});
        v.push_back({.name = "still, HDR cd/m2 with noise, foveated", .seed = 2, .hdr = true, .foveated = true,
                     .fix = Fix::Fixed, .fx0 = 60, .fy0 = 50, .jod = 9.119439});
        v.push_back({.name = "still, noise, dim display (10 cd/m2, 200:1), 35 ppd", .seed = 3, .noise = 0.1,
                     .ppd = 35, .peak = 10, .contrast = 200, .jod = 9.649905});
        v.push_back({.name = "video, dynamic noise, 20 ppd", .w = 96, .h = 72, .frames = 30, .fps = 30, .seed = 4,
                     .noise = 0.04, .jod = 9.298575});
        v.push_back({.name = "video, dynamic noise, 20 ppd, foveated", .w = 96, .h = 72, .frames = 30, .fps = 30,
                     .seed = 4, .noise = 0.04, .foveated = true, .fix = Fix::Fixed, .fx0 = 20, .fy0 = 20,
                     .jod = 9.481337});
        v.push_back({.name = "video, 10 Hz flicker at 30 fps, 20 ppd", .w = 96, .h = 72, .frames = 30, .fps = 30,
                     .flickerHz = 10, .flickerAmp = 0.03, .jod = 8.553173});
        v.push_back({.name = "video, 30 Hz flicker at 60 fps in a box, 15 ppd, foveated", .w = 96, .h = 72,
                     .frames = 30, .fps = 60, .flickerHz = 30, .flickerAmp = 0.03, .box = {32, 24, 64, 48},
                     .ppd = 15, .foveated = true, .fix = Fix::Fixed, .fx0 = 48, .fy0 = 36, .jod = 8.898016});
        v.push_back({.name = "video, moving content blurred, moving fixation, 25 ppd", .w = 96, .h = 72,
                     .frames = 30, .fps = 30, .blur = true, .vx = 1.0, .ppd = 25, .foveated = true,
                     .fix = Fix::Path, .fx0 = 10, .fy0 = 10, .fx1 = 85, .fy1 = 60, .jod = 8.312635});
        v.push_back({.name = "video, 15 Hz flicker in a box, 1.5-inch monitor at 0.5 m (27.5 ppd), foveated",
                     .w = 96, .h = 72, .frames = 30, .fps = 30, .flickerHz = 15, .flickerAmp = 0.02,
                     .box = {8, 8, 40, 40}, .geo = Geo::Monitor, .diagonalInches = 1.5, .distance = 0.5,
                     .foveated = true, .fix = Fix::Fixed, .fx0 = 70, .fy0 = 50, .jod = 9.375174});
        v.push_back({.name = "video, HDR cd/m2, moving content with noise", .w = 96, .h = 72, .frames = 30,
                     .fps = 30, .seed = 5, .hdr = true, .vx = 0.5, .jod = 8.754881});
        return v;
    }();
    return cases;
}

inline const GoldenCase& CaseNamed(const std::string& name) {
    for (const GoldenCase& c : GoldenCases())
        if (name == c.name) return c;
    FAIL("no case " << name);
    return GoldenCases()[0];
}

}  // namespace fovrt::vdp_test
