#include "app/report_html.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/atomic_file.h"
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

// Summary table (thesis layout) as HTML.
std::string SummaryHtml(const Results& results, const std::string& baseline, const std::string& scene) {
    ReportTable t;
    t.title = fmt::format("Summary: {} (mean over frames and eyes; relMSE ε = {:g}; % vs {})", scene,
                          results.relMseEpsilon, baseline);
    t.header = {"variant", "relMSE", "relMSE fovea", "SSIM", "SSIM fovea", "FLIP", "FLIP fovea",
                "ΔrelMSE", "ΔrelMSE fovea", "ΔSSIM", "ΔSSIM fovea"};
    struct Col {
        const char* metric;
        const char* region;
    };
    const Col cols[] = {{"relmse", "whole"}, {"relmse", "fovea"}, {"ssim", "whole"},
                        {"ssim", "fovea"},   {"flip", "whole"},   {"flip", "fovea"}};
    for (const std::string& variant : results.Variants(scene)) {
        std::vector<std::string> row = {variant};
        for (const Col& c : cols) {
            auto m = results.Mean(scene, variant, c.region, c.metric);
            row.push_back(!m ? "–"
                             : std::string(c.metric) == "relmse" ? fmt::format("{:.3e}", m->mean)
                                                                 : fmt::format("{:.4f}", m->mean));
        }
        for (int k = 0; k < 4; ++k) {
            auto m = results.Mean(scene, variant, cols[k].region, cols[k].metric);
            auto b = results.Mean(scene, baseline, cols[k].region, cols[k].metric);
            std::optional<double> pct;
            if (m && variant != baseline) pct = PercentRelative(m->mean, b ? std::optional<double>(b->mean) : std::nullopt);
            row.push_back(!pct ? "–" : FormatPercent(*pct, k < 2 ? 3 : 4));
        }
        t.rows.push_back(std::move(row));
    }
    return TableHtml(t);
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

// One table per metric: variant × every region (periphery and eccentricity bands included).
std::string RegionTablesHtml(const Results& results, const std::string& scene) {
    std::string out;
    const std::vector<std::string> regions = results.Regions(scene);
    for (const std::string& metric : results.Metrics(scene)) {
        ReportTable t{fmt::format("{} by region (mean over frames and eyes)", metric), {"variant"}, {}};
        for (const std::string& r : regions) t.header.push_back(r);
        for (const std::string& variant : results.Variants(scene)) {
            std::vector<std::string> row = {variant};
            for (const std::string& r : regions) {
                auto m = results.Mean(scene, variant, r, metric);
                row.push_back(!m ? "–" : metric == "relmse" ? fmt::format("{:.3e}", m->mean) : fmt::format("{:.4f}", m->mean));
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

std::string SceneSection(const HtmlReport& report, const SceneVisuals* visuals, const std::string& scene) {
    std::string out = fmt::format("<section><h2>Scene: {}</h2>", HtmlEscape(scene));
    if (report.results) {
        const Results& r = *report.results;
        out += SummaryHtml(r, report.baseline, scene);
        out += "<div class=\"plots\">";
        for (const std::string& metric : r.Metrics(scene))
            for (const char* region : {"whole", "fovea"}) {
                std::vector<PlotSeries> series;
                for (const std::string& variant : r.Variants(scene)) {
                    PlotSeries s{variant, {}};
                    for (const auto& [frame, value] : r.PerFrame(scene, variant, region, metric))
                        s.points.emplace_back(double(frame), value);
                    if (!s.points.empty()) series.push_back(std::move(s));
                }
                if (series.empty()) continue;
                out += SvgLinePlot(fmt::format("{} — {}", metric, region), metric, series, metric == "relmse");
            }
        out += "</div>";
        out += "<details><summary>All regions</summary>" + RegionTablesHtml(r, scene) + "</details>";
    }
    if (visuals) {
        const SceneVisuals& v = *visuals;
        out += fmt::format("<h3>Frame {}, eye {}</h3><div class=\"row\">", v.frame, v.eye);
        if (!v.gazePath.empty())
            out += Figure(SvgGazePath(v.width, v.height, v.gazePath, v.foveaRadiusPixels), "gaze path (pixels)");
        if (!v.sppMap.empty())
            out += Figure(PngImg(DisplayColorPng(FalseColorSpp(v.sppMap)), "spp map", 320),
                          "spp map (viridis, 1 … max spp)");
        out += "</div>";
        if (!v.reference.empty()) {
            // Error maps: log10 relMSE per pixel over [−4, 0].
            out += "<h3>relMSE per pixel (viridis of log10, 1e-4 … 1)</h3><div class=\"row\">";
            auto errorMap = [&](const Plane<vec3>& img) {
                Plane<float> m = Shrink(RelMseMap(img, v.reference), kMapWidth);
                for (size_t i = 0; i < m.size(); ++i) m[i] = std::log10(std::max(m[i], 1e-6f));
                return FalseColorPng(m, -4.0f, 0.0f);
            };
            if (!v.noisy.empty()) out += Figure(PngImg(errorMap(v.noisy), "noisy error", 320), "noisy");
            for (const auto& [name, img] : v.variants) out += Figure(PngImg(errorMap(img), name + " error", 320), name);
            out += "</div>";
            // Fovea crops.
            const int radius = std::max(8, int(std::lround(v.foveaRadiusPixels)));
            out += "<h3>Fovea crops</h3><div class=\"row\">";
            out += Figure(PngImg(EncodePngToMemory(Crop(v.reference, v.gazePixel, radius)), "reference", 240), "reference");
            if (!v.noisy.empty())
                out += Figure(PngImg(EncodePngToMemory(Crop(v.noisy, v.gazePixel, radius)), "noisy", 240), "noisy");
            for (const auto& [name, img] : v.variants)
                out += Figure(PngImg(EncodePngToMemory(Crop(img, v.gazePixel, radius)), name, 240), name);
            out += "</div>";
        }
    }
    return out + "</section>";
}

constexpr const char* kCss = R"(body{font-family:system-ui,sans-serif;margin:24px;color:#222;max-width:1400px}
h1{font-size:22px}h2{font-size:18px;border-bottom:1px solid #ccc;padding-bottom:4px}h3{font-size:15px}
table{border-collapse:collapse;margin:8px 0;font-size:13px}td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}
th{background:#f3f3f3}td:first-child,th:first-child{text-align:left}
.row,.plots{display:flex;flex-wrap:wrap;gap:12px}figure{margin:0}figcaption{font-size:12px;text-align:center}
img{image-rendering:pixelated;border:1px solid #ddd}svg{background:#fff;border:1px solid #ddd}
.note{font-size:12px;color:#555})";

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

std::vector<uint8_t> FalseColorPng(const Plane<float>& values, float lo, float hi) {
    Plane<vec3> colors(values.width(), values.height());
    const float range = hi > lo ? hi - lo : 1.0f;
    for (size_t i = 0; i < values.size(); ++i) colors[i] = Viridis((values[i] - lo) / range);
    return DisplayColorPng(colors);
}

Plane<vec3> Crop(const Plane<vec3>& image, const vec2& centre, int radius) {
    const int side = std::max(1, 2 * radius);
    int x0 = int(std::floor(centre.x)) - radius, y0 = int(std::floor(centre.y)) - radius;
    x0 = std::clamp(x0, 0, std::max(0, image.width() - side));
    y0 = std::clamp(y0, 0, std::max(0, image.height() - side));
    const int w = std::min(side, image.width()), h = std::min(side, image.height());
    Plane<vec3> out(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) out(x, y) = image(x0 + x, y0 + y);
    return out;
}

std::string SvgLinePlot(const std::string& title, const std::string& yLabel, const std::vector<PlotSeries>& series,
                        bool logY) {
    constexpr double kW = 420, kH = 240, kLeft = 62, kRight = 110, kTop = 24, kBottom = 30;
    double xMin = std::numeric_limits<double>::infinity(), xMax = -xMin, yMin = xMin, yMax = -xMin;
    auto mapY = [&](double y) { return logY ? std::log10(y) : y; };
    for (const PlotSeries& s : series)
        for (const auto& [x, y] : s.points) {
            if (!std::isfinite(y) || (logY && y <= 0)) continue;
            xMin = std::min(xMin, x), xMax = std::max(xMax, x);
            yMin = std::min(yMin, mapY(y)), yMax = std::max(yMax, mapY(y));
        }
    std::string out = fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\">"
        "<text x=\"{2}\" y=\"16\" font-size=\"13\" font-family=\"sans-serif\">{3}</text>",
        kW, kH, kLeft, HtmlEscape(title));
    if (!std::isfinite(xMin)) return out + "<text x=\"60\" y=\"120\" font-size=\"12\">no data</text></svg>";
    if (xMax == xMin) xMax = xMin + 1;
    if (yMax == yMin) yMax = yMin + (yMin == 0 ? 1 : std::abs(yMin) * 0.1);
    const double pad = 0.05 * (yMax - yMin);  // keep lines off the frame
    yMin -= pad, yMax += pad;
    const double pw = kW - kLeft - kRight, ph = kH - kTop - kBottom;
    auto px = [&](double x) { return kLeft + (x - xMin) / (xMax - xMin) * pw; };
    auto py = [&](double y) { return kTop + (1 - (mapY(y) - yMin) / (yMax - yMin)) * ph; };
    out += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#999\"/>", kLeft,
                       kTop, pw, ph);
    auto label = [&](double v) { return fmt::format("{:.3g}", logY ? std::pow(10.0, v) : v); };
    out += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"10\" text-anchor=\"end\">{}</text>", kLeft - 4, kTop + 8,
                       label(yMax));
    out += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"10\" text-anchor=\"end\">{}</text>", kLeft - 4,
                       kTop + ph, label(yMin));
    out += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"10\">frame {:g}</text>", kLeft, kH - 8, xMin);
    out += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"10\" text-anchor=\"end\">{:g}</text>", kLeft + pw,
                       kH - 8, xMax);
    out += fmt::format("<text x=\"12\" y=\"{}\" font-size=\"10\" transform=\"rotate(-90 12 {})\">{}{}</text>",
                       kTop + ph / 2, kTop + ph / 2, HtmlEscape(yLabel), logY ? " (log)" : "");
    for (size_t k = 0; k < series.size(); ++k) {
        std::string pts;
        for (const auto& [x, y] : series[k].points) {
            if (!std::isfinite(y) || (logY && y <= 0)) continue;
            pts += fmt::format("{:.1f},{:.1f} ", px(x), py(y));
        }
        out += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\" points=\"{}\"/>",
                           SeriesColor(k), pts);
        out += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"10\" height=\"3\" fill=\"{}\"/>"
                           "<text x=\"{}\" y=\"{}\" font-size=\"11\">{}</text>",
                           kLeft + pw + 8, kTop + 8 + 16 * double(k), SeriesColor(k), kLeft + pw + 22,
                           kTop + 13 + 16 * double(k), HtmlEscape(series[k].name));
    }
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
    std::string out = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" +
                      HtmlEscape(report.title) + "</title><style>" + kCss + "</style></head><body>";
    out += "<h1>" + HtmlEscape(report.title) + "</h1>";
    out += fmt::format(
        "<p class=\"note\">relMSE = mean((y−r)²/(r²+ε)) per channel on HDR, ε = {:g}. SSIM (Wang 2004, 11×11 "
        "Gaussian σ = 1.5, K1 = 0.01, K2 = 0.03) on the luma of the tonemapped image (clamp to [0,1], sRGB "
        "encode). FLIP: LDR-FLIP on the same tonemap at the eye's pixels per degree. Regions: fovea = gaze-centred "
        "disc, periphery = its complement, eccentricity bands by view-ray angle to the gaze ray.</p>",
        report.results ? report.results->relMseEpsilon : 0.01);
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
        out += SceneSection(report, visuals, scene);
    }
    for (const ReportTable& t : report.tables) out += TableHtml(t);
    return out + "</body></html>\n";
}

void WriteHtmlReport(const std::filesystem::path& path, const HtmlReport& report) {
    WriteTextAtomically(path, RenderHtmlReport(report));
}

}  // namespace fovrt
