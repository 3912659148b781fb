// The self-contained HTML report: one file that opens offline (inline CSS, inline SVG plots,
// base64 PNG images, no external references). Its one inline script paints the full frames at the
// exposure the page's slider picks, records script errors and marks every figure once the
// browser has drawn it (data-drawn="1", or "0" for an image that failed to decode, a plot with
// nothing in it or a frame not painted) and sets
// data-report-check="ok" on <body> when all of them drew — the browser check
// (tests/report_browser_check.sh) reads that from headless Chromium's DOM.
//
// Per scene: the summary table (ExperimentStats: mean, median, geometric mean; paired ratio to
// the baseline with its bootstrap interval, ns when it contains 1; win rate; temporal error next
// to relMSE) with the method stated, the outlier frames that dominate a mean, per-frame plots of
// every metric (whole and fovea) per variant with axis ticks, a legend under the plot, blinks and
// saccades shaded and the outlier frames marked, the gaze speed, the gaze path, the spp map and
// false-colour relMSE maps (viridis of log10 relMSE per pixel), each with its colour bar, the
// FovVideoVDP maps, each variant's per-pixel relMSE ratio to the baseline, the full frames of
// reference / noisy / each variant with an exposure slider (the script paints them from RGBE
// images), and fovea crops of the same. Then whatever tables the caller passes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/experiment_stats.h"
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

// What the gaze did on one frame: a blink (invalid sample), and its angular speed since the
// previous valid sample (0 when unknown). A frame faster than kSaccadeDegPerSecond is a saccade
// (velocity threshold, I-VT; smooth pursuit stays below it).
inline constexpr double kSaccadeDegPerSecond = 100.0;
struct GazeMark {
    int frame = 0;
    bool blink = false;
    double speedDegPerSecond = 0.0;
    double timeSeconds = 0.0;
    // Where the eye looks (the true gaze, head space, Fick yaw + = right and pitch + = up, degrees);
    // 0 in a blink.
    double yawDeg = 0.0, pitchDeg = 0.0;
    // The rendered fovea (the tracked gaze's spp disc) against the true gaze: their angle, and
    // whether the true gaze fell outside the disc (app/gaze_tracking_report.h).
    double foveaDistanceDeg = 0.0;
    bool outsideFovea = false;
    // Past the end of a gaze trace or recording held on its last row (gaze.trace_end = "hold").
    bool gazeHeld = false;
    bool Saccade() const { return !blink && speedDegPerSecond > kSaccadeDegPerSecond; }
};

// Images of one scene at one (frame, eye), all width × height HDR, for the visual section.
struct SceneVisuals {
    std::string scene;
    int width = 0;
    int height = 0;
    int frame = 0;
    int eye = 0;
    uint32_t seed = 1;               // the run seed the images and gaze marks come from
    std::vector<GazeMark> gazeMarks; // one per frame, in order
    std::vector<vec2> gazePath;      // gaze pixel per frame (this eye), may leave the image
    float foveaRadiusPixels = 200.0f;
    vec2 gazePixel{0.0f};            // at `frame`: centre of the fovea crops
    float exposure = 0.0f;           // output.exposure: the images as the PNG outputs show them
    Plane<uint16_t> sppMap;          // optional (empty = not shown)
    Plane<vec3> reference;           // optional; needed for error maps and crops
    Plane<vec3> noisy;               // optional
    std::vector<std::pair<std::string, Plane<vec3>>> variants;  // denoised outputs by variant
    std::map<std::string, Plane<float>> vdpMaps;  // FovVideoVDP difference map at `frame` by variant
};

struct HtmlReport {
    std::string title = "fovrt report";
    std::vector<std::pair<std::string, std::string>> manifest;  // key, value (config, seed, ...)
    const Results* results = nullptr;
    const ExperimentStats* stats = nullptr;  // nullptr: computed from results with `baseline`
    std::string baseline;                    // "" = each scene's first variant
    std::vector<SceneVisuals> scenes;
    std::vector<ReportTable> tables;  // memory table, per-pass timings, ...
    // At the top, under the title: the headline tables, then figures (inline SVG, e.g. SvgLinePlot).
    std::vector<ReportTable> headline;
    std::vector<std::string> plots;
};

std::string RenderHtmlReport(const HtmlReport& report);
void WriteHtmlReport(const std::filesystem::path& path, const HtmlReport& report);

// Building blocks (exposed for tests).
std::string Base64(const std::vector<uint8_t>& bytes);
std::string HtmlEscape(const std::string& text);
vec3 Viridis(float t);  // t in [0,1]
// Blue (0) – light grey (1/2) – red (1), for signed differences (ColorBrewer RdBu ends).
vec3 Diverging(float t);
// PNG of a scalar map through viridis, values mapped linearly from [lo, hi].
std::vector<uint8_t> FalseColorPng(const Plane<float>& values, float lo, float hi);
// The same through Diverging: lo blue, the middle grey, hi red.
std::vector<uint8_t> DivergingPng(const Plane<float>& values, float lo, float hi);
// Ward's RGBE of an HDR image: 8-bit mantissas (3 per pixel) and a shared exponent per pixel
// E = e + 128 for a largest channel in [2^(e−1), 2^e), 0 for black; radiance ≈ (m + 0.5)/256 · 2^(E − 128).
struct RgbeImage {
    std::vector<uint8_t> mantissa, exponent;
};
RgbeImage EncodeRgbe(const Plane<vec3>& hdr);
// The display byte of every RGBE (E, m), entry E·256 + m: PNG's display transform (io/png.h,
// exposure 0) of (m + 0.5)/256 · 2^(E − 128); row 0 is black. An exposure of k stops is row E + k.
std::vector<uint8_t> DisplayLut();
// The pixels Crop takes from a width × height image: a square of side 2·radius around centre,
// moved inside the image (x0, y0: its top-left pixel).
struct CropRect {
    int x0 = 0, y0 = 0, width = 0, height = 0;
};
CropRect CropRectOf(int width, int height, const vec2& centre, int radius);
// Those pixels of `image`.
Plane<vec3> Crop(const Plane<vec3>& image, const vec2& centre, int radius);

struct PlotSeries {
    std::string name;
    std::vector<std::pair<double, double>> points;  // (x, y)
    int color = -1;  // palette index, so that a series keeps its colour across plots; -1: its position
};
struct LinePlot {
    std::string title;
    std::string xLabel = "frame";
    std::string yLabel;
    std::vector<PlotSeries> series;
    bool logY = false;                    // plots log10(y); non-positive values are skipped
    bool logX = false;                    // plots log10(x) (ticks at 1, 2, 5 × 10^k); x ≤ 0 is skipped
    bool markers = false;                 // a dot at every point (sparse data: a sweep's curves)
    std::vector<double> blinkX, saccadeX; // x of blink / saccade frames: shaded bands
    std::vector<double> markedX;          // x of outlier frames: a marker above the plot
    std::optional<double> thresholdY;     // a dashed horizontal line (e.g. the saccade speed)
};
// An inline SVG line plot with ticks on both axes and the legend under the plot area.
std::string SvgLinePlot(const LinePlot& plot);
// Nice tick values covering [lo, hi]: linear steps of 1, 2 or 5 × 10^k (about `target` of them);
// with `log`, lo and hi are log10 values and the ticks are log10 of 1, 2, 5 × 10^k (or only the
// powers of ten when there are many decades).
std::vector<double> AxisTicks(double lo, double hi, bool log, int target = 5);
// A horizontal colour bar (SVG) for a viridis map over [lo, hi] with the given tick labels at
// their positions t in [0, 1].
std::string SvgColorBar(int width, const std::vector<std::pair<double, std::string>>& ticks,
                        const std::string& label, vec3 (*ramp)(float) = Viridis);
// The gaze path as an SVG polyline over a width × height frame, with the fovea disc at the end.
std::string SvgGazePath(int width, int height, const std::vector<vec2>& path, float foveaRadius);

}  // namespace fovrt
