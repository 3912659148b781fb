#include "app/report_html.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "app/report_summary.h"
#include "config/settings_tables.h"
#include "io/png.h"
#include "metrics/image_metrics.h"

namespace fovrt {

namespace {

// One colour per variant, in order (colour-blind-friendly Okabe–Ito palette).
const char* SeriesColor(size_t i) {
    static const char* colors[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"};
    return colors[i % 7];
}

std::string PngImg(const std::vector<uint8_t>& png, const std::string& alt, int displayWidth = 0) {
    std::string width = displayWidth > 0 ? fmt::format(" width=\"{}\"", displayWidth) : "";
    return fmt::format("<img alt=\"{}\"{} src=\"data:image/png;base64,{}\">", HtmlEscape(alt), width, Base64(png));
}

std::string Figure(const std::string& inner, const std::string& caption) {
    return fmt::format("<figure>{}<figcaption>{}</figcaption></figure>", inner, HtmlEscape(caption));
}

std::string TableHtml(const ReportTable& t) {
    std::string out = fmt::format("<h3>{}</h3><table><tr>", HtmlEscape(t.title));
    for (const std::string& h : t.header) out += "<th>" + HtmlEscape(h) + "</th>";
    out += "</tr>";
    for (const auto& row : t.rows) {
        out += "<tr>";
        for (const std::string& cell : row) out += "<td>" + HtmlEscape(cell) + "</td>";
        out += "</tr>";
    }
    return out + "</table>";
}

std::string Sci(double v) { return std::isfinite(v) ? fmt::format("{:.3e}", v) : "–"; }
std::string Fixed(double v) { return std::isfinite(v) ? fmt::format("{:.4f}", v) : "–"; }
std::string MetricValue(const std::string& metric, double v) { return metric == "relmse" || metric == "temporal" ? Sci(v) : Fixed(v); }

std::string MetricLabel(const std::string& metric) {
    if (metric == "relmse") return "relMSE";
    if (metric == "ssim") return "SSIM";
    if (metric == "flip") return "FLIP";
    if (metric == "temporal") return "temporal";
    return metric;
}

// "0.823 [0.791, 0.861]" in a cell; an interval that contains 1 is greyed and marked ns.
std::string RatioCell(const std::optional<PairedRatio>& r, bool isBaseline) {
    if (isBaseline) return "<td class=\"base\">baseline</td>";
    if (!r || r->pairs == 0) return "<td>–</td>";
    // The ratio over its interval, so the summary's four ratio columns fit a 1400-pixel page.
    std::string text = HtmlEscape(FormatRatio(*r));
    if (const size_t space = text.find(' '); space != std::string::npos)
        text = text.substr(0, space) + "<br><span class=\"ci\">" + text.substr(space + 1) + "</span>";
    return fmt::format("<td class=\"{}\" title=\"{} pairs, blocks of {} frames\">{}</td>",
                       r->Significant() ? "sig" : "ns", r->pairs, r->blockLength, text);
}

// The summary of one scene: variant × region rows; relMSE (mean, median, geometric mean, ratio,
// win rate), temporal error (mean, ratio) beside it, then SSIM and FLIP (mean, ratio).
std::string SummaryHtml(const Results& results, const ExperimentStats& stats, const std::string& scene) {
    const SceneDesign& d = stats.Design(scene);
    std::string seeds;
    for (uint32_t s : d.seeds) seeds += (seeds.empty() ? "" : ", ") + std::to_string(s);
    std::string out = fmt::format(
        "<h3>Summary: {} — {} seed{} ({}) × {} frames × {} eyes, baseline {}</h3>", HtmlEscape(scene), d.seeds.size(),
        d.seeds.size() == 1 ? "" : "s", seeds, d.frames, d.eyes, HtmlEscape(d.baseline));
    out += "<table class=\"summary\"><tr><th rowspan=\"2\">variant</th><th rowspan=\"2\">region</th>"
           "<th colspan=\"5\">relMSE</th><th colspan=\"2\">temporal error</th><th colspan=\"2\">SSIM</th>"
           "<th colspan=\"2\">FLIP</th></tr><tr><th>mean</th><th>median</th><th>geo. mean</th>"
           "<th>ratio [95% CI]</th><th>win</th><th>mean</th><th>ratio [95% CI]</th><th>mean</th>"
           "<th>ratio [95% CI]</th><th>mean</th><th>ratio [95% CI]</th></tr>";
    for (const std::string& variant : results.Variants(scene))
        for (const std::string& region : ComparedRegions()) {
            const MetricStats* e = stats.Find(scene, variant, region, "relmse");
            if (!e) continue;
            const bool isBase = variant == d.baseline;
            out += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>", HtmlEscape(variant),
                               region, Sci(e->spread.mean), Sci(e->spread.median),
                               e->spread.count > 0 && std::isnan(e->spread.geometricMean)
                                   ? "<span title=\"a frame has an error of exactly 0: undefined\">n/a</span>"
                                   : Sci(e->spread.geometricMean));
            out += RatioCell(e->vsBaseline, isBase);
            out += isBase || !e->vsBaseline || e->vsBaseline->pairs == 0
                       ? std::string("<td>–</td>")
                       : fmt::format("<td>{:.0f}%</td>", 100.0 * e->vsBaseline->winRate);
            for (const char* metric : {"temporal", "ssim", "flip"}) {
                const MetricStats* m = stats.Find(scene, variant, region, metric);
                out += fmt::format("<td>{}</td>", m ? MetricValue(metric, m->spread.mean) : "–");
                out += m ? RatioCell(m->vsBaseline, isBase) : "<td>–</td>";
            }
            out += "</tr>";
        }
    out += "</table>";
    // The frames that dominate a mean.
    std::string outliers;
    for (const std::string& variant : results.Variants(scene))
        for (const std::string& region : ComparedRegions())
            for (const std::string& metric : results.Metrics(scene)) {
                const MetricStats* m = stats.Find(scene, variant, region, metric);
                if (!m || BetterOf(metric) != Better::kLower || !m->dominant.Dominates()) continue;
                std::string frames;
                for (size_t i = 0; i < m->dominant.frames.size() && i < 12; ++i)
                    frames += (i ? ", " : "") + std::to_string(m->dominant.frames[i]);
                if (m->dominant.frames.size() > 12) frames += ", …";
                outliers += fmt::format("<li>{} {} {}: {} of {} frames ({}) hold {:.0f}% of the mean</li>",
                                        HtmlEscape(variant), region, MetricLabel(metric), m->dominant.frames.size(),
                                        m->dominant.totalFrames, frames, 100.0 * m->dominant.share);
            }
    out += outliers.empty()
               ? "<p class=\"note\">No mean is dominated by outlier frames (no fifth of the frames holds half of "
                 "any mean error).</p>"
               : "<p class=\"note\">Outlier frames (value per frame = mean over eyes and seeds; marked ▼ on the "
                 "plots):</p><ul class=\"note\">" + outliers + "</ul>";
    return out;
}

// Box-average by an integer factor so that the width is at most maxWidth (keeps the file small;
// fovea crops stay at full resolution).
template <typename T>
Plane<T> Shrink(const Plane<T>& in, int maxWidth) {
    const int f = std::max(1, (in.width() + maxWidth - 1) / maxWidth);
    if (f == 1) return in;
    const int w = std::max(1, in.width() / f), h = std::max(1, in.height() / f);
    Plane<T> out(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            T sum{};
            for (int j = 0; j < f; ++j)
                for (int i = 0; i < f; ++i) sum += in(x * f + i, y * f + j);
            out(x, y) = sum / float(f * f);
        }
    return out;
}

constexpr int kMapWidth = 480;

// One table per metric: variant × every region (periphery and eccentricity bands included):
// mean, median and geometric mean.
std::string RegionTablesHtml(const Results& results, const ExperimentStats& stats, const std::string& scene) {
    std::string out;
    const std::vector<std::string> regions = results.Regions(scene);
    for (const std::string& metric : results.Metrics(scene)) {
        ReportTable t{fmt::format("{} by region (mean / median / geometric mean over frames, eyes and seeds)", metric),
                      {"variant"}, {}};
        for (const std::string& r : regions) t.header.push_back(r);
        for (const std::string& variant : results.Variants(scene)) {
            std::vector<std::string> row = {variant};
            for (const std::string& r : regions) {
                const MetricStats* m = stats.Find(scene, variant, r, metric);
                row.push_back(!m || m->spread.count == 0
                                  ? "–"
                                  : fmt::format("{} / {} / {}", MetricValue(metric, m->spread.mean),
                                                MetricValue(metric, m->spread.median),
                                                MetricValue(metric, m->spread.geometricMean)));
            }
            t.rows.push_back(std::move(row));
        }
        out += TableHtml(t);
    }
    return out;
}

Plane<vec3> FalseColorSpp(const Plane<uint16_t>& spp) {
    uint16_t maxSpp = 2;
    for (size_t i = 0; i < spp.size(); ++i) maxSpp = std::max(maxSpp, spp[i]);
    Plane<vec3> out(spp.width(), spp.height());
    for (size_t i = 0; i < spp.size(); ++i) out[i] = Viridis(float(int(spp[i]) - 1) / float(maxSpp - 1));
    return Shrink(out, kMapWidth);
}

std::vector<uint8_t> DisplayColorPng(const Plane<vec3>& displayRgb) {
    std::vector<uint8_t> rgb(displayRgb.size() * 3);
    for (size_t i = 0; i < displayRgb.size(); ++i)
        for (int c = 0; c < 3; ++c)
            rgb[3 * i + size_t(c)] = uint8_t(std::lround(std::clamp(displayRgb[i][c], 0.0f, 1.0f) * 255.0f));
    return EncodeRgb8Png(displayRgb.width(), displayRgb.height(), rgb);
}

// The colour bar of the relMSE maps: viridis over log10 relMSE in [−4, 0].
std::string RelMseColorBar() {
    std::vector<std::pair<double, std::string>> ticks;
    for (int e = -4; e <= 0; ++e) ticks.emplace_back(double(e + 4) / 4.0, e == 0 ? "1" : fmt::format("1e{}", e));
    return SvgColorBar(320, ticks, "relMSE per pixel (log scale)");
}

// The colour bar of the difference-to-baseline maps: log10 of the per-pixel relMSE ratio.
std::string RatioColorBar(const std::string& baseline) {
    return SvgColorBar(320, {{0.0, "1/10"}, {0.25, "1/3"}, {0.5, "1"}, {0.75, "3"}, {1.0, "10"}},
                       "relMSE ratio per pixel (variant / " + baseline + ")", Diverging);
}

// The report's full frames as two PNGs (mantissas RGB, exponent grey) of their RGBE at the PNG
// outputs' exposure, which the page's script shows at any whole stop through DisplayLut, without
// a second copy of the display transform.
std::pair<std::vector<uint8_t>, std::vector<uint8_t>> RgbePngs(const Plane<vec3>& hdr, float exposure) {
    Plane<vec3> exposed = hdr;
    for (size_t i = 0; i < exposed.size(); ++i) exposed[i] *= std::exp2(exposure);
    const RgbeImage rgbe = EncodeRgbe(exposed);
    std::vector<uint8_t> grey(rgbe.exponent.size() * 3);
    for (size_t i = 0; i < grey.size(); ++i) grey[i] = rgbe.exponent[i / 3];
    return {EncodeRgb8Png(hdr.width(), hdr.height(), rgbe.mantissa), EncodeRgb8Png(hdr.width(), hdr.height(), grey)};
}

const std::string& DisplayLutBase64() {
    static const std::string lut = Base64(DisplayLut());
    return lut;
}

// The page's exposure slider in whole stops over the PNGs' exposure: output.exposure's slider span
// (config/settings_tables.cpp), as the preview panel offers it, and always 0.
std::pair<int, int> ExposureSliderStops(float exposure) {
    const ParamRange span = SliderSpan(OutputTable(), "output.exposure");
    return {std::min(0, int(std::ceil(span.min - exposure))), std::max(0, int(std::floor(span.max - exposure)))};
}

// A full frame the page shows at the exposure its slider picks (the script paints the canvas
// from the RGBE images beside it).
std::string HdrFigure(const Plane<vec3>& image, float exposure, const std::string& caption) {
    const auto [mantissa, exponent] = RgbePngs(image, exposure);
    return fmt::format("<figure><canvas class=\"hdr\" width=\"{}\" height=\"{}\" title=\"{}\"></canvas>"
                       "<img class=\"rgbe-m\" hidden alt=\"{} (RGBE mantissas)\" src=\"data:image/png;base64,{}\">"
                       "<img class=\"rgbe-e\" hidden alt=\"{} (RGBE exponents)\" src=\"data:image/png;base64,{}\">"
                       "<figcaption>{}</figcaption></figure>",
                       image.width(), image.height(), HtmlEscape(caption), HtmlEscape(caption), Base64(mantissa),
                       HtmlEscape(caption), Base64(exponent), HtmlEscape(caption));
}

std::string SppColorBar(int maxSpp) {
    std::vector<std::pair<double, std::string>> ticks;
    const int step = std::max(1, (maxSpp - 1 + 3) / 4);
    for (int spp = 1; spp <= maxSpp; spp += step) ticks.emplace_back(double(spp - 1) / double(maxSpp - 1), std::to_string(spp));
    if ((maxSpp - 1) % step != 0) ticks.emplace_back(1.0, std::to_string(maxSpp));
    return SvgColorBar(320, ticks, "samples per pixel");
}

std::string SceneSection(const HtmlReport& report, const ExperimentStats* stats, const SceneVisuals* visuals,
                         const std::string& scene) {
    std::string out = fmt::format("<section><h2>Scene: {}</h2>", HtmlEscape(scene));
    if (report.results && stats) {
        const Results& r = *report.results;
        out += SummaryHtml(r, *stats, scene);
        // Gaze events and outlier frames shared by every plot of the scene.
        std::vector<double> blinks, saccades, outlierFrames;
        if (visuals)
            for (const GazeMark& m : visuals->gazeMarks) {
                if (m.blink) blinks.push_back(m.frame);
                if (m.Saccade()) saccades.push_back(m.frame);
            }
        out += fmt::format("<h3>Per frame (mean over eyes and seeds)</h3><p class=\"note\">Shaded: blinks (grey) "
                           "and saccades (orange: gaze faster than {:g}°/s between frames{}); ▼ frames that hold half "
                           "of a variant's mean (listed above).</p><div class=\"plots\">",
                           kSaccadeDegPerSecond, visuals ? fmt::format(", seed {}", visuals->seed) : "");
        for (const std::string& metric : r.Metrics(scene))
            for (const char* region : {"whole", "fovea"}) {
                LinePlot plot;
                plot.title = fmt::format("{} — {}", metric, region);
                plot.yLabel = MetricLabel(metric);
                plot.logY = metric == "relmse";
                plot.blinkX = blinks;
                plot.saccadeX = saccades;
                for (const std::string& variant : r.Variants(scene)) {
                    PlotSeries s{variant, {}};
                    for (const auto& [frame, value] : r.PerFrame(scene, variant, region, metric))
                        s.points.emplace_back(double(frame), value);
                    if (!s.points.empty()) plot.series.push_back(std::move(s));
                    const MetricStats* m = stats->Find(scene, variant, region, metric);
                    if (m && BetterOf(metric) == Better::kLower && m->dominant.Dominates())
                        for (int f : m->dominant.frames)
                            if (std::find(plot.markedX.begin(), plot.markedX.end(), double(f)) == plot.markedX.end())
                                plot.markedX.push_back(f);
                }
                if (plot.series.empty()) continue;
                out += SvgLinePlot(plot);
            }
        if (visuals && !visuals->gazeMarks.empty()) {
            LinePlot speed;
            speed.title = "gaze speed (head space)";
            speed.yLabel = "°/s";
            speed.blinkX = blinks;
            speed.saccadeX = saccades;
            speed.thresholdY = kSaccadeDegPerSecond;
            PlotSeries s{"gaze", {}};
            for (const GazeMark& m : visuals->gazeMarks)
                if (!m.blink) s.points.emplace_back(double(m.frame), m.speedDegPerSecond);
            speed.series.push_back(std::move(s));
            out += SvgLinePlot(speed);
        }
        out += "</div>";
        out += "<details><summary>All regions</summary>" + RegionTablesHtml(r, *stats, scene) + "</details>";
    }
    if (visuals) {
        const SceneVisuals& v = *visuals;
        out += fmt::format("<h3>Frame {}, eye {}, seed {}</h3><div class=\"row\">", v.frame, v.eye, v.seed);
        if (!v.gazePath.empty())
            out += Figure(SvgGazePath(v.width, v.height, v.gazePath, v.foveaRadiusPixels), "gaze path (pixels)");
        if (!v.sppMap.empty()) {
            uint16_t maxSpp = 2;
            for (size_t i = 0; i < v.sppMap.size(); ++i) maxSpp = std::max(maxSpp, v.sppMap[i]);
            out += Figure(PngImg(DisplayColorPng(FalseColorSpp(v.sppMap)), "spp map", 320) + SppColorBar(maxSpp),
                          "spp map");
        }
        out += "</div>";
        if (!v.reference.empty()) {
            // Error maps: log10 relMSE per pixel over [−4, 0], each with its colour bar.
            out += "<h3>relMSE per pixel (viridis of log10, 1e-4 … 1)</h3><div class=\"row\">";
            auto errorMap = [&](const Plane<vec3>& img) {
                Plane<float> m = Shrink(RelMseMap(img, v.reference), kMapWidth);
                for (size_t i = 0; i < m.size(); ++i) m[i] = std::log10(std::max(m[i], 1e-6f));
                return FalseColorPng(m, -4.0f, 0.0f);
            };
            if (!v.noisy.empty())
                out += Figure(PngImg(errorMap(v.noisy), "noisy error", 320) + RelMseColorBar(), "noisy");
            for (const auto& [name, img] : v.variants)
                out += Figure(PngImg(errorMap(img), name + " error", 320) + RelMseColorBar(), name);
            out += "</div>";
            // The perceptual metric's difference maps of the same frame, on one scale for all variants.
            if (!v.vdpMaps.empty()) {
                float top = 1e-6f;
                for (const auto& [name, map] : v.vdpMaps)
                    for (size_t i = 0; i < map.size(); ++i) top = std::max(top, map[i]);
                out += fmt::format("<h3>FovVideoVDP difference map (JOD loss per pixel, viridis over 0 … {:.3g}; "
                                   "foveated at the true gaze)</h3><div class=\"row\">", top);
                for (const auto& [name, img] : v.variants)
                    if (auto it = v.vdpMaps.find(name); it != v.vdpMaps.end())
                        out += Figure(PngImg(FalseColorPng(Shrink(it->second, kMapWidth), 0.0f, top),
                                             name + " FovVideoVDP map", 320), name);
                out += "</div>";
            }
            // Each variant against the baseline, pixel by pixel: where it gains, where it loses.
            const std::string baseline = !report.baseline.empty() ? report.baseline
                                         : v.variants.empty()     ? std::string()
                                                                  : v.variants.front().first;
            const Plane<vec3>* base = nullptr;
            for (const auto& [name, img] : v.variants)
                if (name == baseline) base = &img;
            if (base && v.variants.size() > 1) {
                const Plane<float> baseError = Shrink(RelMseMap(*base, v.reference), kMapWidth);
                out += fmt::format("<h3>Difference to {}: log10 of the per-pixel relMSE ratio (blue: the variant's "
                                   "error is lower, red: higher)</h3><div class=\"row\">",
                                   HtmlEscape(baseline));
                for (const auto& [name, img] : v.variants) {
                    if (&img == base) continue;
                    Plane<float> ratio = Shrink(RelMseMap(img, v.reference), kMapWidth);
                    for (size_t i = 0; i < ratio.size(); ++i)
                        ratio[i] = std::log10(std::max(ratio[i], 1e-9f) / std::max(baseError[i], 1e-9f));
                    out += Figure(PngImg(DivergingPng(ratio, -1.0f, 1.0f), name + " vs " + baseline, 320) +
                                      RatioColorBar(baseline),
                                  name + " vs " + baseline);
                }
                out += "</div>";
            }
            // Full frames at an exposure the reader picks (the PNGs' exposure at 0).
            const auto [lowest, highest] = ExposureSliderStops(v.exposure);
            out += fmt::format("<h3>Full frames (frame {}, eye {}, seed {})</h3><p class=\"note\">Exposure "
                               "<input type=\"range\" class=\"exposure\" min=\"{}\" max=\"{}\" step=\"1\" "
                               "value=\"0\"><output>0</output> stops over output.exposure ({:+g}); the display "
                               "transform of the PNG outputs (clamp, sRGB).</p><div class=\"row\">",
                               v.frame, v.eye, v.seed, lowest, highest, v.exposure);
            out += HdrFigure(v.reference, v.exposure, "reference");
            if (!v.noisy.empty()) out += HdrFigure(v.noisy, v.exposure, "noisy");
            for (const auto& [name, img] : v.variants) out += HdrFigure(img, v.exposure, name);
            out += "</div>";
            // Fovea crops.
            const int radius = std::max(8, int(std::lround(v.foveaRadiusPixels)));
            // The rectangle in the heading: a crop can be cut again from the full frames.
            const CropRect rect = CropRectOf(v.reference.width(), v.reference.height(), v.gazePixel, radius);
            out += fmt::format("<h3>Fovea crops: x {}–{}, y {}–{} of {}×{} (gaze at pixel ({:.1f}, {:.1f}))</h3>"
                               "<div class=\"row\">",
                               rect.x0, rect.x0 + rect.width - 1, rect.y0, rect.y0 + rect.height - 1,
                               v.reference.width(), v.reference.height(), v.gazePixel.x, v.gazePixel.y);
            auto crop = [&](const Plane<vec3>& img) { return EncodePngToMemory(Crop(img, v.gazePixel, radius), v.exposure); };
            out += Figure(PngImg(crop(v.reference), "reference", 240), "reference");
            if (!v.noisy.empty()) out += Figure(PngImg(crop(v.noisy), "noisy", 240), "noisy");
            for (const auto& [name, img] : v.variants) out += Figure(PngImg(crop(img), name, 240), name);
            out += "</div>";
        }
    }
    return out + "</section>";
}

// The report's only script. It paints each full frame (canvas.hdr) from its RGBE images through
// the display LUT (DisplayLutBase64, on <body data-display-lut>) at the stops its section's
// slider says, marking it data-painted="1". It records script errors (window "error" events,
// console.error) in <html data-errors>, and after the page has loaded marks every image, SVG
// figure and frame canvas data-drawn="1" when it drew (an image decoded to a non-zero size; an
// SVG with a non-empty bounding box and, for a plot, every series a polyline with points; a
// canvas painted), else "0", and sets <body data-report-check="ok"> when every figure drew and no
// error was seen ("failed" otherwise). In a window 1400 px wide or wider, a summary table that
// does not fit the page counts as an error.
constexpr const char* kCheckScript = R"(<script>
(function(){
var errors=[];function note(m){errors.push(String(m));document.documentElement.setAttribute('data-errors',errors.join(' | '));}
window.addEventListener('error',function(e){note(e.message||('failed to load '+((e.target&&(e.target.src||e.target.href))||'a resource').slice(0,80)));},true);
var ce=console.error;console.error=function(){note(Array.prototype.join.call(arguments,' '));ce.apply(console,arguments);};
function pixels(img){var c=document.createElement('canvas');c.width=img.naturalWidth;c.height=img.naturalHeight;
var x=c.getContext('2d');x.drawImage(img,0,0);return x.getImageData(0,0,c.width,c.height).data;}
function frames(){var b64=document.body.getAttribute('data-display-lut');if(!b64)return;
var raw=atob(b64),lut=new Uint8Array(raw.length);for(var i=0;i<raw.length;i++)lut[i]=raw.charCodeAt(i);
function paint(c,stop){if(!c._m){var f=c.parentNode;c._m=pixels(f.querySelector('img.rgbe-m'));c._e=pixels(f.querySelector('img.rgbe-e'));}
var x=c.getContext('2d'),out=x.createImageData(c.width,c.height),o=out.data,m=c._m,e=c._e;
for(var i=0;i<o.length;i+=4){var E=e[i]===0?0:Math.min(255,Math.max(1,e[i]+stop))*256;
o[i]=lut[E+m[i]];o[i+1]=lut[E+m[i+1]];o[i+2]=lut[E+m[i+2]];o[i+3]=255;}
x.putImageData(out,0,0);c.setAttribute('data-painted','1');}
document.querySelectorAll('input.exposure').forEach(function(s){var sec=s.closest('section');
function go(){var stop=parseInt(s.value,10);s.nextElementSibling.textContent=(stop>0?'+':'')+stop;
sec.querySelectorAll('canvas.hdr').forEach(function(c){paint(c,stop);});}
s.addEventListener('input',go);go();});}
window.addEventListener('load',function(){
try{frames();}catch(err){note(err);}
if(window.innerWidth>=1400)document.querySelectorAll('table.summary').forEach(function(t){
if(t.getBoundingClientRect().right>document.documentElement.clientWidth+0.5)note('a summary table is wider than the page at '+window.innerWidth+' px');});
var figures=document.querySelectorAll('img, svg, canvas.hdr'),drawn=0,failed=0;
figures.forEach(function(f){var ok,tag=f.tagName.toLowerCase();
if(tag==='img'){ok=f.complete&&f.naturalWidth>0&&f.naturalHeight>0;}
else if(tag==='canvas'){ok=f.getAttribute('data-painted')==='1';}
else{var b=f.getBBox();ok=b.width>0&&b.height>0;
if(f.classList.contains('plot')){var lines=f.querySelectorAll('polyline.series');ok=ok&&lines.length>0;
lines.forEach(function(l){if(!l.points||l.points.numberOfItems<1)ok=false;});}}
f.setAttribute('data-drawn',ok?'1':'0');if(ok)drawn++;else failed++;});
document.body.setAttribute('data-figures-drawn',String(drawn));
document.body.setAttribute('data-report-check',failed===0&&errors.length===0&&drawn===figures.length?'ok':'failed');
});
})();
</script>)";

constexpr const char* kCss = R"(body{font-family:system-ui,sans-serif;margin:24px;color:#222;max-width:1400px}
h1{font-size:22px}h2{font-size:18px;border-bottom:1px solid #ccc;padding-bottom:4px}h3{font-size:15px}
table{border-collapse:collapse;margin:8px 0;font-size:13px}td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}
th{background:#f3f3f3}td:first-child,th:first-child{text-align:left}
.row,.plots{display:flex;flex-wrap:wrap;gap:12px}figure{margin:0}figcaption{font-size:12px;text-align:center}
img{image-rendering:pixelated;border:1px solid #ddd;display:block}img[hidden]{display:none}svg{background:#fff;border:1px solid #ddd}
.note{font-size:12px;color:#555}td.ns{color:#888}td.sig{font-weight:600}td.base{color:#555;font-style:italic}
table.summary td{white-space:nowrap}table.summary{font-size:12px}span.ci{font-size:11px;color:inherit}
svg.colorbar{border:none;display:block;margin:2px auto 0}canvas.hdr{width:400px;image-rendering:pixelated;border:1px solid #ddd;display:block}
input.exposure{vertical-align:middle;width:220px}output{display:inline-block;min-width:2.5em;font-weight:600})";

}  // namespace

std::string Base64(const std::vector<uint8_t>& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        uint32_t v = (uint32_t(bytes[i]) << 16) | (uint32_t(bytes[i + 1]) << 8) | bytes[i + 2];
        out += table[(v >> 18) & 63];
        out += table[(v >> 12) & 63];
        out += table[(v >> 6) & 63];
        out += table[v & 63];
    }
    if (i < bytes.size()) {
        uint32_t v = uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(bytes[i + 1]) << 8;
        out += table[(v >> 18) & 63];
        out += table[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

std::string HtmlEscape(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

vec3 Viridis(float t) {
    // matplotlib's viridis at t = 0, 1/8, …, 1 (#440154 … #fde725), linearly interpolated.
    static const vec3 stops[9] = {{0x44, 0x01, 0x54}, {0x47, 0x2d, 0x7b}, {0x3b, 0x52, 0x8b},
                                  {0x2c, 0x72, 0x8e}, {0x21, 0x91, 0x8c}, {0x28, 0xae, 0x80},
                                  {0x5e, 0xc9, 0x62}, {0xad, 0xdc, 0x30}, {0xfd, 0xe7, 0x25}};
    if (!std::isfinite(t)) t = 0.0f;
    float s = std::clamp(t, 0.0f, 1.0f) * 8.0f;
    int i = std::min(int(s), 7);
    return glm::mix(stops[i], stops[i + 1], s - float(i)) / 255.0f;
}

vec3 Diverging(float t) {
    static const vec3 stops[3] = {{0x21, 0x66, 0xac}, {0xf7, 0xf7, 0xf7}, {0xb2, 0x18, 0x2b}};
    if (!std::isfinite(t)) t = 0.5f;
    const float s = std::clamp(t, 0.0f, 1.0f) * 2.0f;
    const int i = std::min(int(s), 1);
    return glm::mix(stops[i], stops[i + 1], s - float(i)) / 255.0f;
}

namespace {

std::vector<uint8_t> RampPng(const Plane<float>& values, float lo, float hi, vec3 (*ramp)(float)) {
    Plane<vec3> colors(values.width(), values.height());
    const float range = hi > lo ? hi - lo : 1.0f;
    for (size_t i = 0; i < values.size(); ++i) colors[i] = ramp((values[i] - lo) / range);
    return DisplayColorPng(colors);
}

}  // namespace

std::vector<uint8_t> FalseColorPng(const Plane<float>& values, float lo, float hi) {
    return RampPng(values, lo, hi, Viridis);
}

std::vector<uint8_t> DivergingPng(const Plane<float>& values, float lo, float hi) {
    return RampPng(values, lo, hi, Diverging);
}

RgbeImage EncodeRgbe(const Plane<vec3>& hdr) {
    RgbeImage out{std::vector<uint8_t>(hdr.size() * 3, 0), std::vector<uint8_t>(hdr.size(), 0)};
    for (size_t i = 0; i < hdr.size(); ++i) {
        const vec3 c = glm::max(hdr[i], vec3(0.0f));
        const float top = std::max(c.r, std::max(c.g, c.b));
        if (!(top > 1e-30f) || !std::isfinite(top)) continue;
        int e = 0;
        std::frexp(top, &e);  // top = f · 2^e, f in [0.5, 1)
        if (e + 128 < 1 || e + 128 > 255) continue;
        const float toMantissa = std::ldexp(256.0f, -e);
        for (int k = 0; k < 3; ++k) out.mantissa[3 * i + size_t(k)] = uint8_t(std::min(255.0f, c[k] * toMantissa));
        out.exponent[i] = uint8_t(e + 128);
    }
    return out;
}

std::vector<uint8_t> DisplayLut() {
    Plane<vec3> values(256, 256);
    for (int e = 0; e < 256; ++e)
        for (int m = 0; m < 256; ++m)
            values(m, e) = vec3(e == 0 ? 0.0f : std::ldexp((float(m) + 0.5f) / 256.0f, e - 128));
    const std::vector<uint8_t> rgb = TonemapToRgb8(values);
    std::vector<uint8_t> lut(values.size());
    for (size_t i = 0; i < lut.size(); ++i) lut[i] = rgb[3 * i];
    return lut;
}

CropRect CropRectOf(int width, int height, const vec2& centre, int radius) {
    const int side = std::max(1, 2 * radius);
    CropRect r;
    r.x0 = std::clamp(int(std::floor(centre.x)) - radius, 0, std::max(0, width - side));
    r.y0 = std::clamp(int(std::floor(centre.y)) - radius, 0, std::max(0, height - side));
    r.width = std::min(side, width);
    r.height = std::min(side, height);
    return r;
}

Plane<vec3> Crop(const Plane<vec3>& image, const vec2& centre, int radius) {
    const CropRect r = CropRectOf(image.width(), image.height(), centre, radius);
    Plane<vec3> out(r.width, r.height);
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) out(x, y) = image(r.x0 + x, r.y0 + y);
    return out;
}

std::vector<double> AxisTicks(double lo, double hi, bool log, int target) {
    std::vector<double> ticks;
    if (!(std::isfinite(lo) && std::isfinite(hi))) return ticks;
    if (hi < lo) std::swap(lo, hi);
    if (log && hi - lo >= 0.3) {
        // 1, 2, 5 × 10^k, or only the powers of ten when that would be too many.
        const int k0 = int(std::floor(lo)), k1 = int(std::ceil(hi));
        const bool decadesOnly = (k1 - k0) * 3 > 2 * target;
        for (int k = k0; k <= k1; ++k)
            for (double m : {1.0, 2.0, 5.0}) {
                if (decadesOnly && m != 1.0) continue;
                const double t = double(k) + std::log10(m);
                if (t >= lo - 1e-9 && t <= hi + 1e-9) ticks.push_back(t);
            }
        if (ticks.size() >= 2) return ticks;
        ticks.clear();
    }
    if (log) {
        // Less than half a decade: linear ticks in value, placed at their log10.
        for (double v : AxisTicks(std::pow(10.0, lo), std::pow(10.0, hi), false, target)) ticks.push_back(std::log10(v));
        return ticks;
    }
    const double span = hi > lo ? hi - lo : std::max(std::abs(lo), 1.0);
    const double raw = span / std::max(1, target);
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    double step = magnitude;
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * magnitude >= raw) {
            step = m * magnitude;
            break;
        }
    for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step)
        ticks.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
    return ticks;
}

std::string SvgColorBar(int width, const std::vector<std::pair<double, std::string>>& ticks, const std::string& label,
                        vec3 (*ramp)(float)) {
    // 64 solid steps (no gradient: no element ids to keep unique in the document).
    constexpr double kPad = 14, kBarH = 10;
    constexpr int kSteps = 64;
    const double barW = width - 2 * kPad;
    std::string out = fmt::format(
        "<svg class=\"colorbar\" xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"44\" viewBox=\"0 0 {0} "
        "44\" font-family=\"sans-serif\">",
        width);
    for (int i = 0; i < kSteps; ++i) {
        const vec3 c = ramp((float(i) + 0.5f) / float(kSteps));
        out += fmt::format("<rect x=\"{:.2f}\" y=\"2\" width=\"{:.2f}\" height=\"{}\" fill=\"#{:02x}{:02x}{:02x}\"/>",
                           kPad + barW * i / kSteps, barW / kSteps + 0.3, kBarH, int(std::lround(c.r * 255)),
                           int(std::lround(c.g * 255)), int(std::lround(c.b * 255)));
    }
    out += fmt::format("<rect x=\"{}\" y=\"2\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#666\" "
                       "stroke-width=\"0.5\"/>",
                       kPad, barW, kBarH);
    for (const auto& [t, text] : ticks) {
        const double x = kPad + std::clamp(t, 0.0, 1.0) * barW;
        out += fmt::format("<line x1=\"{0:.1f}\" x2=\"{0:.1f}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#333\"/>"
                           "<text x=\"{0:.1f}\" y=\"{3}\" font-size=\"10\" text-anchor=\"middle\">{4}</text>",
                           x, 2 + kBarH, 5 + kBarH, 15 + kBarH + 1, HtmlEscape(text));
    }
    out += fmt::format("<text x=\"{}\" y=\"42\" font-size=\"10\" text-anchor=\"middle\" fill=\"#555\">{}</text></svg>",
                       width / 2, HtmlEscape(label));
    return out;
}

std::string SvgLinePlot(const LinePlot& plot) {
    constexpr double kW = 440, kLeft = 64, kRight = 16, kTop = 34, kPlotH = 170, kAxisH = 34;
    constexpr double kLegendRow = 16, kCharW = 6.4;
    const bool logY = plot.logY, logX = plot.logX;
    double xMin = std::numeric_limits<double>::infinity(), xMax = -xMin, yMin = xMin, yMax = -xMin;
    auto mapY = [&](double y) { return logY ? std::log10(y) : y; };
    auto mapX = [&](double x) { return logX ? std::log10(x) : x; };
    auto skip = [&](double x, double y) { return !std::isfinite(y) || !std::isfinite(x) || (logY && y <= 0) || (logX && x <= 0); };
    for (const PlotSeries& s : plot.series)
        for (const auto& [x, y] : s.points) {
            if (skip(x, y)) continue;
            xMin = std::min(xMin, mapX(x)), xMax = std::max(xMax, mapX(x));
            yMin = std::min(yMin, mapY(y)), yMax = std::max(yMax, mapY(y));
        }
    if (plot.thresholdY && (!logY || *plot.thresholdY > 0) && std::isfinite(yMin)) {
        yMin = std::min(yMin, mapY(*plot.thresholdY));
        yMax = std::max(yMax, mapY(*plot.thresholdY));
    }
    // Legend under the plot: series, then the marks that appear, wrapped to the width.
    struct Entry {
        std::string name;
        std::string swatch;  // SVG of the symbol at (0, 0)
    };
    std::vector<Entry> entries;
    auto color = [&](size_t k) { return SeriesColor(plot.series[k].color >= 0 ? size_t(plot.series[k].color) : k); };
    for (size_t k = 0; k < plot.series.size(); ++k)
        entries.push_back({plot.series[k].name, fmt::format("<rect x=\"0\" y=\"-4\" width=\"14\" height=\"3\" fill=\"{}\"/>",
                                                            color(k))});
    if (!plot.blinkX.empty())
        entries.push_back({"blink", "<rect x=\"0\" y=\"-9\" width=\"14\" height=\"10\" fill=\"#999\" fill-opacity=\"0.35\"/>"});
    if (!plot.saccadeX.empty())
        entries.push_back({"saccade", "<rect x=\"0\" y=\"-9\" width=\"14\" height=\"10\" fill=\"#E69F00\" fill-opacity=\"0.3\"/>"});
    if (!plot.markedX.empty())
        entries.push_back({"outlier frame", "<path d=\"M2,-9 L12,-9 L7,-1 Z\" fill=\"#B00\"/>"});
    if (plot.thresholdY)
        entries.push_back({fmt::format("threshold {:g}", *plot.thresholdY),
                           "<line x1=\"0\" x2=\"14\" y1=\"-3\" y2=\"-3\" stroke=\"#B00\" stroke-dasharray=\"3,2\"/>"});
    std::string legend;
    double lx = kLeft, ly = 0;
    int rows = entries.empty() ? 0 : 1;
    for (const Entry& e : entries) {
        const double w = 22 + kCharW * double(e.name.size()) + 12;
        if (lx + w > kW - 4 && lx > kLeft) lx = kLeft, ly += kLegendRow, ++rows;
        legend += fmt::format("<g transform=\"translate({:.1f},{:.1f})\">{}<text x=\"20\" y=\"0\" font-size=\"11\">{}</text></g>",
                              lx, ly, e.swatch, HtmlEscape(e.name));
        lx += w;
    }
    const double kH = kTop + kPlotH + kAxisH + kLegendRow * rows + 6;
    std::string out = fmt::format(
        "<svg class=\"plot\" xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
        "font-family=\"sans-serif\"><text x=\"{2}\" y=\"16\" font-size=\"13\">{3}</text>",
        kW, kH, kLeft, HtmlEscape(plot.title));
    if (!std::isfinite(xMin))
        return out + fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"12\">no data</text></svg>", kLeft, kTop + kPlotH / 2);
    if (xMax == xMin) xMin -= logX ? 0.1 : 0.5, xMax += logX ? 0.1 : 0.5;
    if (logX) {  // keep the end points off the frame
        const double xPad = 0.05 * (xMax - xMin);
        xMin -= xPad, xMax += xPad;
    }
    if (yMax == yMin) yMin -= (yMin == 0 ? 1 : std::abs(yMin) * 0.1), yMax += (yMax == 0 ? 1 : std::abs(yMax) * 0.1);
    const double pad = 0.05 * (yMax - yMin);  // keep lines off the frame
    yMin -= pad, yMax += pad;
    const double pw = kW - kLeft - kRight, ph = kPlotH;
    auto pxMapped = [&](double m) { return kLeft + (m - xMin) / (xMax - xMin) * pw; };
    auto px = [&](double x) { return pxMapped(mapX(x)); };
    auto pyMapped = [&](double m) { return kTop + (1 - (m - yMin) / (yMax - yMin)) * ph; };
    auto py = [&](double y) { return pyMapped(mapY(y)); };
    // Frame bands (one frame wide, centred on the frame) for blinks and saccades.
    const double frameW = std::max(1.5, pw / std::max(1.0, xMax - xMin + 1));
    auto bands = [&](const std::vector<double>& xs, const char* color, double opacity) {
        for (double x : xs)
            if (x >= xMin - 0.5 && x <= xMax + 0.5)
                out += fmt::format("<rect x=\"{:.1f}\" y=\"{}\" width=\"{:.1f}\" height=\"{}\" fill=\"{}\" "
                                   "fill-opacity=\"{}\"/>",
                                   std::max(kLeft, px(x) - frameW / 2), kTop, frameW, ph, color, opacity);
    };
    bands(plot.blinkX, "#999", 0.35);
    bands(plot.saccadeX, "#E69F00", 0.3);
    out += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#999\"/>", kLeft, kTop,
                       pw, ph);
    // Y ticks, with light grid lines.
    auto yLabel = [&](double m) {
        const double v = logY ? std::pow(10.0, m) : m;
        return fmt::format("{:.3g}", v);
    };
    for (double t : AxisTicks(yMin, yMax, logY, 5)) {
        const double y = pyMapped(t);
        out += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2:.1f}\" y2=\"{2:.1f}\" stroke=\"#eee\"/>"
                           "<line x1=\"{3}\" x2=\"{0}\" y1=\"{2:.1f}\" y2=\"{2:.1f}\" stroke=\"#666\"/>"
                           "<text x=\"{4}\" y=\"{5:.1f}\" font-size=\"10\" text-anchor=\"end\">{6}</text>",
                           kLeft, kLeft + pw, y, kLeft - 4, kLeft - 6, y + 3.5, yLabel(t));
    }
    // X ticks (integers: frames; on a log axis 1, 2, 5 × 10^k).
    for (double t : AxisTicks(xMin, xMax, logX, 6)) {
        if (!logX && std::abs(t - std::round(t)) > 1e-9) continue;
        const double x = pxMapped(t);
        out += fmt::format("<line x1=\"{0:.1f}\" x2=\"{0:.1f}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#666\"/>"
                           "<text x=\"{0:.1f}\" y=\"{3}\" font-size=\"10\" text-anchor=\"middle\">{4:.3g}</text>",
                           x, kTop + ph, kTop + ph + 4, kTop + ph + 15, logX ? std::pow(10.0, t) : t);
    }
    out += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"10\" text-anchor=\"middle\">{}{}</text>", kLeft + pw / 2,
                       kTop + ph + 28, HtmlEscape(plot.xLabel), logX ? " (log)" : "");
    out += fmt::format("<text x=\"12\" y=\"{0}\" font-size=\"10\" text-anchor=\"middle\" transform=\"rotate(-90 12 {0})\">"
                       "{1}{2}</text>",
                       kTop + ph / 2, HtmlEscape(plot.yLabel), logY ? " (log)" : "");
    if (plot.thresholdY && (!logY || *plot.thresholdY > 0))
        out += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2:.1f}\" y2=\"{2:.1f}\" stroke=\"#B00\" "
                           "stroke-dasharray=\"3,2\"/>",
                           kLeft, kLeft + pw, py(*plot.thresholdY));
    for (double x : plot.markedX)
        if (!logX && x >= xMin && x <= xMax)
            out += fmt::format("<path d=\"M{0:.1f},{1} l-4,-7 l8,0 Z\" fill=\"#B00\"><title>frame {2:g}</title></path>",
                               px(x), kTop - 1, x);
    for (size_t k = 0; k < plot.series.size(); ++k) {
        std::string pts, dots;
        for (const auto& [x, y] : plot.series[k].points) {
            if (skip(x, y)) continue;
            pts += fmt::format("{:.1f},{:.1f} ", px(x), py(y));
            if (plot.markers)
                dots += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3\" fill=\"{}\"><title>{:.3g}, {:.4g}</title></circle>",
                                    px(x), py(y), color(k), x, y);
        }
        out += fmt::format("<polyline class=\"series\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\" points=\"{}\"/>",
                           color(k), pts) + dots;
    }
    out += fmt::format("<g transform=\"translate(0,{:.1f})\">{}</g>", kTop + ph + kAxisH + 12, legend);
    return out + "</svg>";
}

std::string SvgGazePath(int width, int height, const std::vector<vec2>& path, float foveaRadius) {
    const double scale = 360.0 / std::max(1, width);
    std::string out = fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0f}\" height=\"{:.0f}\" viewBox=\"0 0 {} {}\">"
        "<rect x=\"0\" y=\"0\" width=\"{}\" height=\"{}\" fill=\"#f7f7f7\" stroke=\"#666\"/>",
        width * scale, height * scale, width, height, width, height);
    std::string pts;
    for (const vec2& p : path) pts += fmt::format("{:.1f},{:.1f} ", p.x, p.y);
    const double stroke = std::max(1.0, 1.5 / scale);
    out += fmt::format("<polyline fill=\"none\" stroke=\"#0072B2\" stroke-width=\"{:.2f}\" points=\"{}\"/>", stroke, pts);
    if (!path.empty()) {
        const vec2& p = path.back();
        out += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{:.1f}\" fill=\"none\" stroke=\"#D55E00\" "
                           "stroke-width=\"{:.2f}\"/>",
                           p.x, p.y, foveaRadius, stroke);
    }
    return out + "</svg>";
}

std::string RenderHtmlReport(const HtmlReport& report) {
    std::optional<ExperimentStats> localStats;
    const ExperimentStats* stats = report.stats;
    if (!stats && report.results) stats = &localStats.emplace(*report.results, report.baseline);
    // The full frames' display LUT, once, when a scene shows them.
    const bool frames = std::ranges::any_of(report.scenes, [](const SceneVisuals& v) { return !v.reference.empty(); });
    const std::string lut = frames ? " data-display-lut=\"" + DisplayLutBase64() + "\"" : "";
    std::string out = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" +
                      HtmlEscape(report.title) + "</title><style>" + kCss + "</style>" + kCheckScript +
                      "</head><body" + lut + ">";
    out += "<h1>" + HtmlEscape(report.title) + "</h1>";
    for (const ReportTable& t : report.headline) out += TableHtml(t);
    if (!report.plots.empty()) {
        out += "<div class=\"plots\">";
        for (const std::string& plot : report.plots) out += plot;
        out += "</div>";
    }
    // The metrics' definitions, where the page shows them (a sweep's page links to its points').
    if (report.results || !report.scenes.empty())
        out += fmt::format(
        "<p class=\"note\">relMSE = mean((y−r)²/(r²+ε)) per channel on HDR, ε = {:g}. SSIM (Wang 2004, 11×11 "
        "Gaussian σ = 1.5, K1 = 0.01, K2 = 0.03) on the luma of the tonemapped image (clamp to [0,1], sRGB "
        "encode). FLIP: LDR-FLIP on the same tonemap at the eye's pixels per degree. Temporal error (SVGF §5.4): "
        "mean |lum(t) − lum(t−1)| of a variant's output, HDR, from each sequence's second frame (flicker; the "
        "reference of these static scenes has none). Regions: fovea = gaze-centred disc, periphery = its "
        "complement, eccentricity bands by view-ray angle to the gaze ray.</p>",
        report.results ? report.results->relMseEpsilon : 0.01);
    if (stats)
        out += "<p class=\"note\"><b>Statistics.</b> " + HtmlEscape(StatisticsMethod(stats->Options())) + "</p>";
    if (!report.manifest.empty()) {
        ReportTable t{"Run", {"key", "value"}, {}};
        for (const auto& [k, v] : report.manifest) t.rows.push_back({k, v});
        out += TableHtml(t);
    }
    std::vector<std::string> scenes = report.results ? report.results->Scenes() : std::vector<std::string>{};
    for (const SceneVisuals& v : report.scenes)
        if (std::find(scenes.begin(), scenes.end(), v.scene) == scenes.end()) scenes.push_back(v.scene);
    for (const std::string& scene : scenes) {
        const SceneVisuals* visuals = nullptr;
        for (const SceneVisuals& v : report.scenes)
            if (v.scene == scene) visuals = &v;
        const bool hasStats = stats && std::ranges::count(stats->Scenes(), scene) > 0;
        out += SceneSection(report, hasStats ? stats : nullptr, visuals, scene);
    }
    for (const ReportTable& t : report.tables) out += TableHtml(t);
    return out + "</body></html>\n";
}

void WriteHtmlReport(const std::filesystem::path& path, const HtmlReport& report) {
    WriteTextAtomically(path, RenderHtmlReport(report));
}

}  // namespace fovrt
