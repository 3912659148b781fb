// The self-contained HTML report: one file that opens offline (inline CSS, inline SVG plots,
// base64 PNG images, no scripts, no external references).
//
// Per scene: per-frame line plots of every metric (whole and fovea) per variant, the gaze path as
// an SVG polyline over the image extent, the spp map, false-colour relMSE maps (viridis of
// log10 relMSE per pixel) and fovea crops of reference / noisy / each variant side by side.
// Then the summary table and whatever tables the caller passes (memory, per-pass timings).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "app/report.h"
#include "core/image.h"
#include "core/math.h"

namespace fovrt {

// A plain table the caller formats (memory budget, per-pass timings, run manifest).
struct ReportTable {
    std::string title;
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
};

// Images of one scene at one (frame, eye), all width × height HDR, for the visual section.
struct SceneVisuals {
    std::string scene;
    int width = 0;
    int height = 0;
    int frame = 0;
    int eye = 0;
    std::vector<vec2> gazePath;      // gaze pixel per frame (this eye), may leave the image
    float foveaRadiusPixels = 200.0f;
    vec2 gazePixel{0.0f};            // at `frame`: centre of the fovea crops
    Plane<uint16_t> sppMap;          // optional (empty = not shown)
    Plane<vec3> reference;           // optional; needed for error maps and crops
    Plane<vec3> noisy;               // optional
    std::vector<std::pair<std::string, Plane<vec3>>> variants;  // denoised outputs by variant
};

struct HtmlReport {
    std::string title = "fovrt report";
    std::vector<std::pair<std::string, std::string>> manifest;  // key, value (config, seed, ...)
    const Results* results = nullptr;
    std::string baseline = kBaselineVariant;
    std::vector<SceneVisuals> scenes;
    std::vector<ReportTable> tables;  // memory table, per-pass timings, ...
};

std::string RenderHtmlReport(const HtmlReport& report);
void WriteHtmlReport(const std::filesystem::path& path, const HtmlReport& report);

// Building blocks (exposed for tests).
std::string Base64(const std::vector<uint8_t>& bytes);
std::string HtmlEscape(const std::string& text);
vec3 Viridis(float t);  // t in [0,1]
// PNG of a scalar map through viridis, values mapped linearly from [lo, hi].
std::vector<uint8_t> FalseColorPng(const Plane<float>& values, float lo, float hi);
// A crop (clamped to the image) of side 2·radius around centre.
Plane<vec3> Crop(const Plane<vec3>& image, const vec2& centre, int radius);

struct PlotSeries {
    std::string name;
    std::vector<std::pair<double, double>> points;  // (x, y)
};
// An inline SVG line plot; logY plots log10(y) (non-positive values are skipped).
std::string SvgLinePlot(const std::string& title, const std::string& yLabel,
                        const std::vector<PlotSeries>& series, bool logY);
// The gaze path as an SVG polyline over a width × height frame, with the fovea disc at the end.
std::string SvgGazePath(int width, int height, const std::vector<vec2>& path, float foveaRadius);

}  // namespace fovrt
