// FovVideoVDP in `fovrt experiment` (app/experiment_vdp.h): every variant scored per (seed, eye)
// sequence at the true gaze, with its outputs (jod.csv, summary.json, the stdout block) and its
// time beside the denoisers' in the manifest.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/config_cli.h"
#include "app/experiment.h"
#include "app/experiment_vdp.h"
#include "app_test_configs.h"
#include "core/error.h"
#include "test_support.h"

using namespace fovrt;
namespace fs = std::filesystem;
using fovrt::test::ReadFile;

namespace {

// One row of jod.csv.
struct JodRow {
    std::string scene, variant;
    uint32_t seed = 0;
    int eye = 0;
    double jod = 0.0, jodSustained = 0.0, jodTransient = 0.0;
};

std::vector<JodRow> ParseJodCsv(const std::string& csv) {
    std::vector<JodRow> rows;
    std::istringstream in(csv);
    std::string line;
    std::getline(in, line);  // the header
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        std::string seed, eye, jod, sustained, transient;
        JodRow r;
        std::getline(fields, r.scene, ',');
        std::getline(fields, seed, ',');
        std::getline(fields, eye, ',');
        std::getline(fields, r.variant, ',');
        std::getline(fields, jod, ',');
        std::getline(fields, sustained, ',');
        std::getline(fields, transient, ',');
        r.seed = uint32_t(std::stoul(seed));
        r.eye = std::stoi(eye);
        r.jod = std::stod(jod);
        r.jodSustained = std::stod(sustained);
        r.jodTransient = std::stod(transient);
        rows.push_back(r);
    }
    return rows;
}

// A 64×36 grey-ramp sequence of 4 frames, and the same with a patch of ±noise centred on `patch`.
struct Sequences {
    std::vector<Plane<vec3>> reference, noisy;
};
Sequences MakeSequences(vec2 patch) {
    Sequences s;
    uint32_t state = 12345u;
    for (int f = 0; f < 4; ++f) {
        Plane<vec3> ref(64, 36), noisy(64, 36);
        for (int y = 0; y < 36; ++y)
            for (int x = 0; x < 64; ++x) {
                const float v = 0.2f + 0.3f * float(x) / 64.0f;
                ref(x, y) = vec3(v);
                state = state * 1664525u + 1013904223u;
                const float n = (float(state >> 8) / float(1u << 24) - 0.5f) * 0.4f;
                const bool inPatch = std::abs(float(x) + 0.5f - patch.x) < 6.0f && std::abs(float(y) + 0.5f - patch.y) < 6.0f;
                noisy(x, y) = vec3(inPatch ? v + n : v);
            }
        s.reference.push_back(ref);
        s.noisy.push_back(noisy);
    }
    return s;
}

// Scores "same" (the reference itself) and "noisy" for eye 0 with the gaze at `gaze` every frame.
std::vector<VdpScore> ScoreAt(const Sequences& s, vec2 gaze) {
    RunConfig config = test::SmallCornellConfig();
    config.camera.width = 64;
    config.camera.height = 36;
    const EyeCamera camera(Pose{}, Fov::FromHorizontal(Radians(90.0f), 64.0f / 36.0f), 64, 36);
    VdpExperimentScorer scorer(config, 30.0, 3);
    for (int f = 0; f < 4; ++f) {
        scorer.AddReference(0, f, camera, s.reference[size_t(f)], gaze);
        scorer.AddOutput(0, "same", s.reference[size_t(f)]);
        scorer.AddOutput(0, "noisy", s.noisy[size_t(f)]);
    }
    std::vector<VdpScore> scores = scorer.Score("ramp", 1);
    REQUIRE(scores.size() == 2u);
    CHECK(scorer.DiffMaps(0).count("noisy") == 1u);
    return scores;
}

}  // namespace

TEST_CASE("experiment FovVideoVDP: identical is 10, noise is below, the fixation matters", "[app][vdp]") {
    const Sequences s = MakeSequences(vec2(10.0f, 18.0f));
    const std::vector<VdpScore> onNoise = ScoreAt(s, vec2(10.0f, 18.0f));
    CHECK(onNoise[0].variant == "same");
    CHECK(onNoise[0].jod == 10.0);
    CHECK(onNoise[0].jodSustained == 10.0);
    CHECK(onNoise[0].jodTransient == 10.0);
    CHECK(onNoise[1].jod < 10.0);
    // The same noise 50 px (over 40° here) from the fixation is less visible.
    const std::vector<VdpScore> away = ScoreAt(s, vec2(60.0f, 18.0f));
    CHECK(away[1].jod > onNoise[1].jod);
    CHECK(away[0].jod == 10.0);
}

TEST_CASE("experiment FovVideoVDP: the display comes from the camera, a profile or overrides", "[app][vdp]") {
    RunConfig config = test::SmallCornellConfig();
    const EyeCamera camera(Pose{}, Fov::FromHorizontal(Radians(90.0f), 2.0f), 200, 100);
    VdpExperimentDisplay d = ExperimentVdpDisplay(config, camera);
    // 200 px over tan 45° × 2: the centre pixel subtends atan(0.01) → 1.745 px/deg.
    CHECK(d.geometry.tanPerPixel == Approx(0.01));
    CHECK(d.photometry.peak == 100.0);
    CHECK(d.photometry.eotf == VdpEotf::Linear);
    config.metric.display = "headset-25";
    d = ExperimentVdpDisplay(config, camera);
    CHECK(d.geometry.PixelsPerDegree() == Approx(25.0).epsilon(1e-3));
    config.metric.ppd = 40.0f;
    config.metric.peak = 250.0f;
    d = ExperimentVdpDisplay(config, camera);
    CHECK(d.geometry.PixelsPerDegree() == Approx(40.0).epsilon(1e-3));
    CHECK(d.photometry.peak == 250.0);
    // The fixation is the gaze pixel less the half pixel the metric adds.
    CHECK(VdpFixationAt(vec2(10.5f, 3.5f)).x == 10.0f);
    CHECK(VdpFixationAt(vec2(10.5f, 3.5f)).y == 3.0f);
}

TEST_CASE("experiment FovVideoVDP: a bad metric.display names the key and the nearest profile", "[app][vdp]") {
    const ConfigOptions options =
        test::ExperimentFileOptions(test::ScratchDir("fovrt_experiment_vdp_test") / "bad",
                                    "[metric]\ndisplay = \"headset-24\"\n"
                                    "[experiment]\nscenes = [\"cornell\"]\nvariants = [\"svgf\"]\n");
    CHECK_THROWS_WITH(LoadExperiment(options),
                      Catch::Contains("metric.display") && Catch::Contains("did you mean 'headset-25'"));
}

TEST_CASE("experiment FovVideoVDP: the JOD table's columns line up under long scene and variant names",
          "[app][vdp]") {
    VdpVariantSummary base;
    base.variant = "svgf";
    base.sequences = 2;
    base.jod = 8.1;
    base.jodSustained = 8.5;
    base.jodTransient = 9.2;
    VdpVariantSummary stable = base;
    stable.variant = "two-history-asvgf-stable-hysteresis";
    stable.difference = 0.014;
    stable.lower = 0.002;
    stable.upper = 0.03;
    stable.pairs = 2;
    const std::string table =
        VdpTable({{"brdf-detail-moving", {base, stable}}, {"cornell", {base, stable}}}, "svgf", "camera");
    INFO(table);
    std::vector<std::string> lines;  // the header and the four rows, after the title line
    std::istringstream in(table);
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line) && !line.empty()) lines.push_back(line);
    REQUIRE(lines.size() == 5);
    const size_t variant = lines[0].find("variant");
    for (const std::string& row : lines) {
        CHECK(row.size() == lines[0].size());  // every later column ends where its header does
        CHECK(row[variant - 1] == ' ');        // the scene name ends before the variant column
    }
    for (size_t i = 1; i < lines.size(); ++i)
        CHECK((lines[i].compare(variant, 5, "svgf ") == 0 || lines[i].compare(variant, 12, "two-history-") == 0));
}

TEST_CASE("experiment FovVideoVDP: JOD per sequence in jod.csv and summary.json", "[app][vdp]") {
    const fs::path dir = test::ScratchDir("fovrt_experiment_vdp_test") / "experiment";
    const ConfigOptions options = test::SmallExperimentOptions(
        dir, {.width = 64, .height = 36, .frames = 4, .referenceSpp = 16, .report = true, .experimentLines = "seeds = [1]\n"});
    RunExperiment(LoadExperiment(options));

    // One row per (seed, eye, variant) sequence.
    const std::string csv = ReadFile(dir / "out" / "jod.csv");
    CHECK(csv.rfind("scene,seed,eye,variant,jod,jod_sustained,jod_transient\n", 0) == 0);
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 5);
    CHECK(csv.find("\ncornell,1,1,two-history,") != std::string::npos);

    const nlohmann::json summary = nlohmann::json::parse(ReadFile(dir / "out" / "summary.json"));
    const nlohmann::json& vdp = summary.at("fovvideovdp");
    CHECK(vdp.at("display").get<std::string>().rfind("camera, ", 0) == 0);
    for (const char* variant : {"svgf", "two-history"}) {
        const nlohmann::json& v = vdp.at("scenes").at("cornell").at(variant);
        // A denoised low-spp frame differs visibly from the 16-spp reference, but is not garbage.
        CHECK(v.at("jod").get<double>() < 10.0);
        CHECK(v.at("jod").get<double>() > 3.0);
        CHECK(v.at("sequences") == 2);
        CHECK(v.contains("jod_sustained"));
        CHECK(v.contains("jod_transient"));
    }
    CHECK_FALSE(vdp["scenes"]["cornell"]["svgf"].contains("vs_baseline"));
    const nlohmann::json& vs = vdp["scenes"]["cornell"]["two-history"]["vs_baseline"];
    CHECK(vs.at("pairs") == 2);
    CHECK(vs.at("lower").get<double>() <= vs.at("difference").get<double>());
    CHECK(vs.at("difference").get<double>() <= vs.at("upper").get<double>());

    // The summary recomputed from jod.csv (9 significant digits): each variant's JODs are the means
    // over its (seed, eye) sequences; the difference to the baseline is the mean of the paired
    // differences, and a bootstrap interval of that mean lies within their range.
    const std::vector<JodRow> rows = ParseJodCsv(csv);
    REQUIRE(rows.size() == 4);
    auto mean = [&](const char* variant, double JodRow::*field) {
        double sum = 0.0;
        int n = 0;
        for (const JodRow& r : rows)
            if (r.variant == variant) sum += r.*field, ++n;
        return sum / n;
    };
    for (const char* variant : {"svgf", "two-history"}) {
        INFO(variant);
        const nlohmann::json& v = vdp["scenes"]["cornell"][variant];
        CHECK(v.at("jod").get<double>() == Approx(mean(variant, &JodRow::jod)).margin(1e-6));
        CHECK(v.at("jod_sustained").get<double>() == Approx(mean(variant, &JodRow::jodSustained)).margin(1e-6));
        CHECK(v.at("jod_transient").get<double>() == Approx(mean(variant, &JodRow::jodTransient)).margin(1e-6));
    }
    std::vector<double> differences;
    for (const JodRow& r : rows)
        for (const JodRow& b : rows)
            if (r.variant == "two-history" && b.variant == "svgf" && r.seed == b.seed && r.eye == b.eye)
                differences.push_back(r.jod - b.jod);
    REQUIRE(differences.size() == 2);
    CHECK(vs.at("difference").get<double>() == Approx((differences[0] + differences[1]) / 2.0).margin(1e-6));
    const auto [lowest, highest] = std::minmax_element(differences.begin(), differences.end());
    CHECK(vs.at("lower").get<double>() >= *lowest - 1e-6);
    CHECK(vs.at("upper").get<double>() <= *highest + 1e-6);
    const std::string html = ReadFile(dir / "out" / "report.html");
    CHECK(html.find("FovVideoVDP JOD") != std::string::npos);
    CHECK(html.find("two-history FovVideoVDP map") != std::string::npos);
    // The manifest says what the metric cost beside the denoisers (both measured in this run).
    const nlohmann::json manifest = nlohmann::json::parse(ReadFile(dir / "out" / "manifest.json"));
    const nlohmann::json& scene = manifest.at("scenes").at(0);
    CHECK(scene.at("metric_ms_per_eye").get<double>() > 0.0);
    CHECK(scene.at("denoise_ms_per_eye").get<double>() > 0.0);
}
