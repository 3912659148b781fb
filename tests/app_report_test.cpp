// Results model, CSV/JSON/table writers and the self-contained HTML report.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/experiment.h"
#include "app/report.h"
#include "app/report_collect.h"
#include "app/report_html.h"
#include "app/report_summary.h"
#include "config/settings_tables.h"
#include "foveation/spp_model.h"
#include "io/png.h"
#include "test_support.h"

using namespace fovrt;

namespace {

Results MakeResults() {
    Results r;
    // Two frames × two eyes; svgf is the baseline, two-history is 10 % better in relMSE.
    for (int frame = 0; frame < 2; ++frame)
        for (int eye = 0; eye < 2; ++eye) {
            const double base = 0.04 + 0.01 * frame + 0.002 * eye;
            r.Add({"cornell", frame, eye, "svgf", "whole", "relmse", base});
            r.Add({"cornell", frame, eye, "svgf", "fovea", "relmse", base / 2});
            r.Add({"cornell", frame, eye, "svgf", "whole", "ssim", 0.9});
            r.Add({"cornell", frame, eye, "svgf", "fovea", "ssim", 0.8});
            r.Add({"cornell", frame, eye, "two-history", "whole", "relmse", 0.9 * base});
            r.Add({"cornell", frame, eye, "two-history", "fovea", "relmse", 0.45 * base});
            r.Add({"cornell", frame, eye, "two-history", "whole", "ssim", 0.91});
            r.Add({"cornell", frame, eye, "two-history", "fovea", "ssim", 0.82});
        }
    return r;
}

std::string ReadFile(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace

TEST_CASE("results: means over frames and eyes, percent vs baseline", "[app][report]") {
    Results r = MakeResults();
    auto m = r.Mean("cornell", "svgf", "whole", "relmse");
    REQUIRE(m);
    CHECK(m->count == 4u);
    CHECK(m->mean == Approx((0.04 + 0.042 + 0.05 + 0.052) / 4));
    auto t = r.Mean("cornell", "two-history", "whole", "relmse");
    CHECK(*PercentRelative(t->mean, m->mean) == Approx(-10.0));
    CHECK_FALSE(r.Mean("cornell", "svgf", "periphery", "relmse"));
    CHECK_FALSE(PercentRelative(1.0, 0.0));
    CHECK(FormatPercent(-0.00001, 4) == "+0.0000%");
    CHECK(FormatPercent(-1.23456, 3) == "-1.235%");
    auto perFrame = r.PerFrame("cornell", "svgf", "whole", "relmse");
    REQUIRE(perFrame.size() == 2u);
    CHECK(perFrame[1].first == 1);
    CHECK(perFrame[1].second == Approx(0.051));
    CHECK(r.Variants("cornell") == std::vector<std::string>{"svgf", "two-history"});
}

TEST_CASE("per-frame CSV has the documented header and one row per value", "[app][report]") {
    Results r = MakeResults();
    r.Add({"other-scene", 0, 0, "svgf", "whole", "relmse", 1.0});
    r.Add({"cornell", 0, 1, "svgf", "whole", "relmse", 0.5, 7});
    std::string csv = FrameCsv(r, "cornell");
    CHECK(csv.rfind("seed,frame,eye,variant,region,metric,value\n", 0) == 0);
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 33);
    CHECK(csv.find("\n1,0,1,svgf,whole,relmse,0.042\n") != std::string::npos);
    CHECK(csv.find("\n7,0,1,svgf,whole,relmse,0.5\n") != std::string::npos);  // every seed's value kept
    CHECK(csv.find("other-scene") == std::string::npos);
    CHECK(FrameCsv(r, "cornell") == csv);  // deterministic
}

TEST_CASE("summary JSON and the table: robust summaries and paired ratios with intervals", "[app][report]") {
    Results r = MakeResults();
    ExperimentStats stats(r);
    nlohmann::json j = SummaryJson(r, stats);
    CHECK(j["relmse_epsilon"].get<double>() == Approx(0.01));
    CHECK(j["method"].get<std::string>().find("circular moving-block bootstrap") != std::string::npos);
    auto& scene = j["scenes"]["cornell"];
    CHECK(scene["baseline"] == "svgf");  // the first variant
    CHECK(scene["seeds"] == nlohmann::json::array({1}));
    auto& th = scene["variants"]["two-history"];
    CHECK(th["fovea"]["relmse"]["percent_vs_baseline"].get<double>() == Approx(-10.0));
    CHECK(th["whole"]["ssim"]["mean"].get<double>() == Approx(0.91));
    CHECK(th["whole"]["relmse"]["median"].get<double>() == Approx(0.9 * 0.046));
    auto& vs = th["fovea"]["relmse"]["vs_baseline"];
    CHECK(vs["ratio"].get<double>() == Approx(0.9));  // 0.45 base / 0.5 base on every frame
    CHECK(vs["ci_low"].get<double>() == Approx(0.9));
    CHECK(vs["ci_high"].get<double>() == Approx(0.9));
    CHECK(vs["significant"] == true);
    CHECK(vs["win_rate"].get<double>() == Approx(1.0));
    CHECK(vs["pairs"] == 4);
    CHECK(scene["variants"]["svgf"]["whole"]["relmse"].count("vs_baseline") == 0);  // the baseline itself
    CHECK(th["whole"]["ssim"]["vs_baseline"]["win_rate"].get<double>() == Approx(1.0));  // higher SSIM wins

    std::string table = SummaryTable(r, stats);
    INFO(table);
    CHECK(table.find("Scene cornell: 1 seed (1) x 2 frames x 2 eyes; baseline svgf") != std::string::npos);
    CHECK(table.find("eps = 0.01") != std::string::npos);
    CHECK(table.find("0.900 [0.900, 0.900]") != std::string::npos);  // relMSE ratio vs svgf
    CHECK(table.find("100%") != std::string::npos);                   // win rate
    CHECK(table.find("4.600e-02") != std::string::npos);              // svgf whole relMSE mean

    // experiment.baseline: any variant.
    ExperimentStats other(r, "two-history");
    CHECK(SummaryJson(r, other)["scenes"]["cornell"]["variants"]["svgf"]["fovea"]["relmse"]["vs_baseline"]["ratio"]
              .get<double>() == Approx(1.0 / 0.9));
}

TEST_CASE("the table marks an interval that contains 1 as not significant", "[app][report]") {
    Results r;
    Pcg32 rng(3);
    for (uint32_t seed = 1; seed <= 3; ++seed)
        for (int frame = 0; frame < 20; ++frame)
            for (int eye = 0; eye < 2; ++eye) {
                const double base = 0.01 + 0.01 * rng.NextFloat();
                r.Add({"s", frame, eye, "svgf", "whole", "relmse", base, seed});
                r.Add({"s", frame, eye, "other", "whole", "relmse", base * (0.9 + 0.2 * rng.NextFloat()), seed});
            }
    ExperimentStats stats(r);
    const MetricStats* m = stats.Find("s", "other", "whole", "relmse");
    REQUIRE(m);
    REQUIRE(m->vsBaseline);
    CHECK_FALSE(m->vsBaseline->Significant());
    CHECK(m->vsBaseline->pairs == 120u);
    CHECK(stats.Design("s").seeds == std::vector<uint32_t>{1, 2, 3});
    std::string table = SummaryTable(r, stats);
    INFO(table);
    CHECK(table.find("] ns") != std::string::npos);
    CHECK(SummaryJson(r, stats)["scenes"]["s"]["variants"]["other"]["whole"]["relmse"]["vs_baseline"]["significant"] ==
          false);
}

TEST_CASE("outlier frames that dominate a mean are named", "[app][report]") {
    Results r;
    for (int frame = 0; frame < 20; ++frame)
        for (const char* variant : {"svgf", "two-history"}) {
            const double value = frame == 7 ? 1.0 : 0.001;  // the light in the fovea
            r.Add({"s", frame, 0, variant, "fovea", "relmse", value * (variant[0] == 't' ? 0.8 : 1.0)});
        }
    ExperimentStats stats(r);
    const MetricStats* m = stats.Find("s", "svgf", "fovea", "relmse");
    REQUIRE(m);
    CHECK(m->dominant.Dominates());
    CHECK(m->dominant.frames == std::vector<int>{7});
    CHECK(m->dominant.share > 0.9);
    const std::string table = SummaryTable(r, stats);
    INFO(table);
    CHECK(table.find("svgf fovea: 1 of 20 frames (7) hold 98% of the mean relMSE") != std::string::npos);
    CHECK(SummaryJson(r, stats)["scenes"]["s"]["variants"]["svgf"]["fovea"]["relmse"]["dominant_frames"]["frames"] ==
          nlohmann::json::array({7}));
}

TEST_CASE("the table's columns line up under a variant name longer than the others", "[app][report]") {
    Results r;
    const std::string longName = "two-history-asvgf-stable-hysteresis";
    for (int frame = 0; frame < 4; ++frame)
        for (const char* region : {"whole", "fovea", "periphery"}) {
            r.Add({"cornell", frame, 0, "svgf", region, "relmse", 0.01 + 0.001 * frame});
            r.Add({"cornell", frame, 0, longName, region, "relmse", 0.009 + 0.001 * frame});
            r.Add({"cornell", frame, 0, "svgf", region, "ssim", 0.9});
            r.Add({"cornell", frame, 0, longName, region, "ssim", 0.91});
        }
    const std::string table = SummaryTable(r, ExperimentStats(r));
    INFO(table);
    // The header and every row: one width, so each column starts where its header does.
    std::vector<std::string> lines;
    std::istringstream in(table);
    for (std::string line; std::getline(in, line);)
        if (line.rfind("variant ", 0) == 0 || line.rfind("svgf ", 0) == 0 || line.rfind(longName + " ", 0) == 0)
            lines.push_back(line);
    REQUIRE(lines.size() == 7);
    const size_t region = lines[0].find("region");
    REQUIRE(region > longName.size());
    for (const std::string& line : lines) {
        CHECK(line.size() == lines[0].size());
        const std::string cell = line.substr(region, 5);
        CHECK((cell == "regio" || cell == "whole" || cell == "fovea" || cell == "perip"));
    }
}

TEST_CASE("base64, escaping and viridis building blocks", "[app][report]") {
    CHECK(Base64({}) == "");
    CHECK(Base64({'f'}) == "Zg==");
    CHECK(Base64({'f', 'o'}) == "Zm8=");
    CHECK(Base64({'f', 'o', 'o', 'b', 'a', 'r'}) == "Zm9vYmFy");
    CHECK(HtmlEscape("<a & \"b\">") == "&lt;a &amp; &quot;b&quot;&gt;");
    CHECK(Viridis(0.0f).r == Approx(0x44 / 255.0f));
    CHECK(Viridis(1.0f).g == Approx(0xe7 / 255.0f));
    CHECK(Viridis(0.5f).b == Approx(0x8c / 255.0f));
    Plane<vec3> img(10, 8, vec3(0.0f));
    img(9, 7) = vec3(1.0f);
    Plane<vec3> crop = Crop(img, vec2(9.5f, 7.5f), 2);  // clamped to the corner
    REQUIRE(crop.width() == 4);
    CHECK(crop(3, 3).x == 1.0f);
    const CropRect rect = CropRectOf(10, 8, vec2(9.5f, 7.5f), 2);
    CHECK((rect.x0 == 6 && rect.y0 == 4 && rect.width == 4 && rect.height == 4));
    const CropRect inside = CropRectOf(10, 8, vec2(4.2f, 3.9f), 2);
    CHECK((inside.x0 == 2 && inside.y0 == 1));
}

TEST_CASE("HTML report is a single offline file with plots, images and tables", "[app][report]") {
    Results r = MakeResults();
    HtmlReport report;
    report.title = "test <report>";
    report.results = &r;
    report.manifest = {{"seed", "42"}};
    SceneVisuals v;
    v.scene = "cornell";
    v.width = 64;
    v.height = 48;
    v.gazePath = {{10, 10}, {20, 15}, {30, 30}};
    v.gazePixel = {30, 30};
    v.foveaRadiusPixels = 8;
    v.sppMap = Plane<uint16_t>(64, 48, 1);
    v.reference = Plane<vec3>(64, 48, vec3(0.5f));
    v.noisy = Plane<vec3>(64, 48, vec3(0.7f));
    v.variants = {{"svgf", Plane<vec3>(64, 48, vec3(0.55f))}, {"two-history", Plane<vec3>(64, 48, vec3(0.45f))}};
    v.vdpMaps["svgf"] = Plane<float>(64, 48, 0.01f);
    v.vdpMaps["two-history"] = Plane<float>(64, 48, 0.02f);
    v.exposure = 1.0f;
    report.scenes.push_back(std::move(v));
    report.tables.push_back({"Memory", {"buffer", "MB"}, {{"two-history extra", "88 B/px"}}});
    report.tables.push_back({"Timings", {"pass", "ms"}, {{"atrous", "1.25"}}});

    const auto dir = std::filesystem::temp_directory_path() / "fovrt_app_report_test";
    std::filesystem::create_directories(dir);
    WriteHtmlReport(dir / "report.html", report);
    std::string html = ReadFile(dir / "report.html");
    CHECK(html.rfind("<!DOCTYPE html>", 0) == 0);
    CHECK(html.find("test &lt;report&gt;") != std::string::npos);
    CHECK(html.find("<style>") != std::string::npos);
    CHECK(html.find("<polyline") != std::string::npos);
    CHECK(html.find("10.0,10.0 20.0,15.0 30.0,30.0") != std::string::npos);  // gaze path
    CHECK(html.find("data:image/png;base64,iVBORw0KGgo") != std::string::npos);  // PNG signature
    CHECK(html.find("relmse — fovea") != std::string::npos);
    CHECK(html.find("ssim by region") != std::string::npos);
    // The paired ratio over its interval (two lines: the summary fits a 1400-pixel page).
    CHECK(html.find("0.900<br><span class=\"ci\">[0.900, 0.900]</span>") != std::string::npos);
    CHECK(html.find("circular moving-block bootstrap") != std::string::npos);  // the method stated
    CHECK(html.find("class=\"colorbar\"") != std::string::npos);       // colour bars
    CHECK(html.find("relMSE per pixel (log scale)") != std::string::npos);
    CHECK(html.find("Memory") != std::string::npos);
    CHECK(html.find("atrous") != std::string::npos);
    CHECK(html.find("ε = 0.01") != std::string::npos);
    // The metric's maps of both variants, one scale (0 … the largest loss).
    CHECK(html.find("FovVideoVDP difference map (JOD loss per pixel, viridis over 0 … 0.02") != std::string::npos);
    CHECK(html.find("alt=\"two-history FovVideoVDP map\"") != std::string::npos);
    // Each variant but the baseline against it, with a diverging colour bar.
    CHECK(html.find("Difference to svgf") != std::string::npos);
    CHECK(html.find("alt=\"two-history vs svgf\"") != std::string::npos);
    CHECK(html.find("alt=\"svgf vs svgf\"") == std::string::npos);
    CHECK(html.find("relMSE ratio per pixel (variant / svgf)") != std::string::npos);
    CHECK(html.find("img[hidden]{display:none}") != std::string::npos);  // the RGBE sources stay hidden
    // Full frames of reference, noisy and both variants, painted from RGBE at the slider's stops
    // through the display LUT (once, on <body>).
    size_t canvases = 0;
    for (size_t at = html.find("<canvas class=\"hdr\""); at != std::string::npos;
         at = html.find("<canvas class=\"hdr\"", at + 1))
        ++canvases;
    CHECK(canvases == 4);
    CHECK(html.find("<canvas class=\"hdr\" width=\"64\" height=\"48\" title=\"reference\">") != std::string::npos);
    // The exposure slider spans output.exposure's row, in stops over the PNGs' exposure (+1).
    const ParamRange exposure = SliderSpan(OutputTable(), "output.exposure");
    const std::string slider =
        fmt::format("class=\"exposure\" min=\"{}\" max=\"{}\"", int(exposure.min) - 1, int(exposure.max) - 1);
    CHECK(html.find(slider) != std::string::npos);
    CHECK(html.find("stops over output.exposure (+1)") != std::string::npos);
    const size_t lut = html.find("data-display-lut=\"");
    REQUIRE(lut != std::string::npos);
    CHECK(html.find("data-display-lut=", lut + 1) == std::string::npos);
    CHECK(html.find('"', lut + 18) - (lut + 18) == Base64(std::vector<uint8_t>(65536)).size());
    // Offline: no external fetches; one inline script (the drawing check), no script file.
    CHECK(html.find("http://") == html.find("http://www.w3.org/2000/svg"));
    CHECK(html.find("https://") == std::string::npos);
    CHECK(html.find("<script src") == std::string::npos);
    CHECK(html.find("<script") == html.rfind("<script"));
    CHECK(html.find("data-report-check") != std::string::npos);
    CHECK(html.find("<link") == std::string::npos);
    std::filesystem::remove_all(dir);
}

TEST_CASE("RGBE full frames: the display LUT shows a pixel as the PNG output does", "[app][report]") {
    Plane<vec3> image(3, 1, vec3(0.0f));
    image(0, 0) = vec3(0.02f, 0.2f, 0.7f);
    image(1, 0) = vec3(3.0f, 1.5f, 0.001f);
    const RgbeImage rgbe = EncodeRgbe(image);
    const std::vector<uint8_t> lut = DisplayLut();
    REQUIRE(lut.size() == 65536);
    CHECK(rgbe.exponent[2] == 0);  // black
    for (int stop : {-2, 0, 3}) {
        Plane<vec3> decoded(3, 1, vec3(0.0f));
        for (size_t i = 0; i < image.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                const int e = rgbe.exponent[i];
                if (e == 0) continue;
                // Within half a mantissa step of the radiance; the LUT at E + stop shows the
                // decoded radiance × 2^stop exactly as the PNG output would.
                const float step = std::ldexp(1.0f / 256.0f, e - 128);
                decoded(int(i), 0)[c] = (float(rgbe.mantissa[3 * i + size_t(c)]) + 0.5f) * step;
                CHECK(std::abs(decoded(int(i), 0)[c] - image(int(i), 0)[c]) <= 0.5f * step);
            }
        const std::vector<uint8_t> png = TonemapToRgb8(decoded, float(stop));
        for (size_t i = 0; i < image.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                const int e = rgbe.exponent[i];
                const size_t row = e == 0 ? 0 : size_t(std::clamp(e + stop, 1, 255)) * 256;
                INFO("pixel " << i << " channel " << c << " stop " << stop);
                CHECK(lut[row + rgbe.mantissa[3 * i + size_t(c)]] == png[3 * i + size_t(c)]);
            }
    }
}

TEST_CASE("per-seed table: each seed's means and its JOD", "[app][report]") {
    Results r = MakeResults();
    r.Add({"cornell", 0, 0, "svgf", "whole", "relmse", 0.5, 7});  // one row of a second seed
    const std::vector<VdpScore> vdp = {{"cornell", 1, 0, "svgf", 9.0}, {"cornell", 1, 1, "svgf", 8.0},
                                       {"cornell", 7, 0, "svgf", 7.5}};
    const ReportTable t = PerSeedTable(r, vdp);
    REQUIRE(t.rows.size() == 4);  // seeds 1 and 7 × svgf, two-history
    CHECK(t.rows[0] == std::vector<std::string>{"cornell", "1", "svgf", "4.600e-02", "2.300e-02", "–", "0.9000", "–",
                                                "8.500"});
    CHECK(t.rows[1][2] == "two-history");
    CHECK(t.rows[1][8] == "–");  // not scored
    CHECK(t.rows[2] == std::vector<std::string>{"cornell", "7", "svgf", "5.000e-01", "–", "–", "–", "–", "7.500"});
}

TEST_CASE("MetricsCollector: regions × metrics per variant, temporal from the second frame", "[app][report]") {
    Results results;
    MetricsCollector collector(results);
    Fov fov;  // 90° × 90°
    EyeCamera camera(Pose{}, fov, 64, 64);
    Plane<vec3> ref(64, 64, vec3(0.5f)), a(64, 64, vec3(0.6f)), b(64, 64, vec3(0.4f));
    for (int frame = 0; frame < 2; ++frame) {
        EyeFrameImages images;
        images.scene = "s";
        images.frame = frame;
        images.eye = 1;
        images.camera = camera;
        images.fovea = FoveaRadius::Pixels(10.0f);
        images.reference = &ref;
        images.outputs = {{"svgf", frame == 0 ? &a : &b}, {"noisy", &a}};
        RegionSet regions = collector.Add(images);
        CHECK(regions.Find("fovea")->pixelCount > 0u);
    }
    // 7 regions (whole, fovea, periphery, 4 bands) × (relmse, ssim, flip) on frame 0, + temporal on frame 1.
    CHECK(results.rows().size() == 2u * 7u * 3u + 2u * 7u * 4u);
    auto relmse = results.Mean("s", "svgf", "fovea", "relmse");
    CHECK(relmse->mean == Approx(0.01 / 0.26).epsilon(1e-4));
    auto temporal = results.Mean("s", "svgf", "whole", "temporal");
    REQUIRE(temporal);
    CHECK(temporal->count == 1u);
    CHECK(temporal->mean == Approx(0.2).epsilon(1e-4));
    CHECK(results.Mean("s", "noisy", "whole", "temporal")->mean == Approx(0.0).margin(1e-9));
    CHECK(results.Mean("s", "svgf", "whole", "flip")->mean > 0.0);
}

TEST_CASE("the pixel fovea region is exactly the disc spp model's sppInside area", "[app][report]") {
    // Off-axis eye, off-centre gaze: metrics and foveation must agree on which pixels are foveal.
    Fov fov;
    fov.angleLeft = Radians(-40.0f), fov.angleRight = Radians(50.0f);
    fov.angleUp = Radians(35.0f), fov.angleDown = Radians(-30.0f);
    EyeCamera camera(Pose{}, fov, 160, 120);
    const vec3 gaze = camera.EyeDirection(vec2(101.3f, 47.8f));
    FoveationParams params;  // disc, 8 inside / 1 outside, 200 px at 1280 wide
    auto model = CreateSppModel(params);
    Plane<uint16_t> spp;
    model->Generate(camera, gaze, 0, spp);
    const float radius = params.radiusPx * 160.0f / float(params.radiusReferenceWidth);  // 25 px
    RegionSet regions = RegionSet::Build(camera, gaze, FoveaRadius::Pixels(radius));
    const Region* fovea = regions.Find("fovea");
    REQUIRE(fovea);
    CHECK(fovea->pixelCount > 1000u);
    for (size_t i = 0; i < spp.size(); ++i) REQUIRE((spp[i] == 8) == (fovea->mask[i] == 1));
}

TEST_CASE("plots: ticks on both axes, the legend under the plot, gaze events and outliers marked", "[app][report]") {
    CHECK(AxisTicks(0.0, 10.0, false, 5) == std::vector<double>{0.0, 2.0, 4.0, 6.0, 8.0, 10.0});
    const std::vector<double> tenths = AxisTicks(0.3, 0.72, false, 5);
    REQUIRE(tenths.size() == 5u);
    CHECK(tenths.front() == Approx(0.3));
    CHECK(tenths.back() == Approx(0.7));
    const std::vector<double> decades = AxisTicks(-4.0, 0.0, true, 5);
    CHECK(decades == std::vector<double>{-4.0, -3.0, -2.0, -1.0, 0.0});
    CHECK(AxisTicks(-2.0, -1.0, true, 5).size() == 4u);  // 0.01, 0.02, 0.05, 0.1

    LinePlot plot;
    plot.title = "relmse — fovea";
    plot.yLabel = "relMSE";
    plot.logY = true;
    plot.series = {{"svgf", {{0, 0.01}, {1, 0.02}, {2, 0.5}}},
                   {"a-long-variant-name-1", {{0, 0.01}}},
                   {"a-long-variant-name-2", {{0, 0.01}}},
                   {"a-long-variant-name-3", {{0, 0.01}}}};
    plot.blinkX = {1};
    plot.saccadeX = {2};
    plot.markedX = {2};
    const std::string svg = SvgLinePlot(plot);
    CHECK(svg.find(">0.01<") != std::string::npos);  // y ticks
    CHECK(svg.find(">0.1<") != std::string::npos);
    CHECK(svg.find(">frame<") != std::string::npos);
    CHECK(svg.find(">blink<") != std::string::npos);
    CHECK(svg.find(">saccade<") != std::string::npos);
    CHECK(svg.find(">outlier frame<") != std::string::npos);
    CHECK(svg.find("<title>frame 2</title>") != std::string::npos);
    // Long names wrap onto more legend rows: the plot grows instead of clipping them.
    LinePlot shortNames = plot;
    shortNames.series.resize(1);
    auto height = [](const std::string& s) {
        const size_t at = s.find("height=\"") + 8;
        return std::stod(s.substr(at, s.find('"', at) - at));
    };
    CHECK(height(svg) > height(SvgLinePlot(shortNames)));
    CHECK(SvgColorBar(320, {{0.0, "1e-4"}, {1.0, "1"}}, "relMSE").find(">1e-4<") != std::string::npos);
}

TEST_CASE("the report states the frames it scored, and the warm-up before them", "[app][report]") {
    RunSettings run;
    run.frames = 8;
    CHECK(ScoredFramesText(run) == "8");
    run.firstFrame = 24;
    run.warmupFrames = 24;
    CHECK(ScoredFramesText(run) == "8 from frame 24, after 24 warm-up frames");
}
