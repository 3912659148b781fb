#include "app/experiment_vdp.h"

#include <algorithm>
#include <cmath>
#include <string_view>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"

namespace fovrt {

std::string VdpDisplayText(const VdpExperimentDisplay& display) {
    return fmt::format("{}, {:.1f} px/deg, {:g} cd/m² peak", display.name, display.geometry.PixelsPerDegree(),
                       display.photometry.peak);
}

VdpExperimentScorer::VdpExperimentScorer(const RunConfig& config, double fps, int visualFrame)
    : config_(config), fps_(fps), visualFrame_(visualFrame) {}

void VdpExperimentScorer::AddReference(int eye, int frame, const EyeCamera& camera, const Plane<vec3>& reference,
                                       const vec2& trueGazePixel) {
    EyeSequences& s = eyes_[size_t(eye)];
    if (!s.camera) {
        s.camera = camera;
        display_ = ExperimentVdpDisplay(config_, camera);
    }
    if (frame == visualFrame_) s.visualPosition = int(s.reference.size());
    s.reference.push_back(VdpDisplayLuminance(reference, config_.output.exposure, display_.photometry));
    s.fixations.push_back(VdpFixationAt(trueGazePixel));
}

void VdpExperimentScorer::AddOutput(int eye, const std::string& variant, const Plane<vec3>& output) {
    EyeSequences& s = eyes_[size_t(eye)];
    auto it = std::find_if(s.variants.begin(), s.variants.end(), [&](const auto& v) { return v.first == variant; });
    if (it == s.variants.end()) it = s.variants.insert(s.variants.end(), {variant, {}});
    it->second.push_back(VdpDisplayLuminance(output, config_.output.exposure, display_.photometry));
}

std::vector<VdpScore> VdpExperimentScorer::Score(const std::string& scene, uint32_t seed) {
    std::vector<VdpScore> scores;
    for (int eye = 0; eye < 2; ++eye) {
        EyeSequences& s = eyes_[size_t(eye)];
        if (!s.camera) continue;
        const FovVideoVdp vdp(ExperimentVdpDisplay(config_, *s.camera).geometry);
        VdpOptions options;
        options.foveated = true;
        options.fixations = s.fixations;
        options.diffMaps = s.visualPosition >= 0;
        for (auto& [variant, frames] : s.variants) {
            if (frames.size() != s.reference.size())
                Fail("FovVideoVDP: {} has {} frames of eye {} but the reference {}", variant, frames.size(), eye,
                     s.reference.size());
            VdpResult r = vdp.Score(frames, s.reference, fps_, options);
            scores.push_back({scene, seed, eye, variant, r.jod, r.jodSustained, r.jodTransient});
            if (options.diffMaps) maps_[size_t(eye)][variant] = std::move(r.diffMaps[size_t(s.visualPosition)]);
            frames.clear();
            frames.shrink_to_fit();
        }
        s = EyeSequences{};
    }
    return scores;
}

std::map<std::string, std::vector<VdpVariantSummary>> SummarizeVdp(const std::vector<VdpScore>& scores,
                                                                   const std::vector<std::string>& variants,
                                                                   const std::string& baseline,
                                                                   const BootstrapOptions& options) {
    std::map<std::string, std::vector<VdpVariantSummary>> out;
    std::vector<std::string> scenes;
    for (const VdpScore& s : scores)
        if (std::find(scenes.begin(), scenes.end(), s.scene) == scenes.end()) scenes.push_back(s.scene);
    for (const std::string& scene : scenes) {
        auto of = [&](const std::string& variant) {
            std::map<std::pair<uint32_t, int>, const VdpScore*> byPair;
            for (const VdpScore& s : scores)
                if (s.scene == scene && s.variant == variant) byPair[{s.seed, s.eye}] = &s;
            return byPair;
        };
        const auto base = of(baseline);
        for (const std::string& variant : variants) {
            const auto mine = of(variant);
            if (mine.empty()) continue;
            VdpVariantSummary v;
            v.variant = variant;
            v.sequences = mine.size();
            for (const auto& [key, s] : mine) {
                v.jod += s->jod / double(mine.size());
                v.jodSustained += s->jodSustained / double(mine.size());
                v.jodTransient += s->jodTransient / double(mine.size());
            }
            if (variant != baseline) {
                // Paired on (seed, eye): both saw the same noisy inputs and the same gaze.
                std::vector<double> differences;
                for (const auto& [key, s] : mine)
                    if (auto b = base.find(key); b != base.end()) differences.push_back(s->jod - b->second->jod);
                if (!differences.empty()) {
                    double mean = 0.0;
                    for (double d : differences) mean += d / double(differences.size());
                    const std::vector<double> means =
                        BlockBootstrapMeans({differences}, 1, options.resamples, options.rngSeed);
                    const double tail = (1.0 - options.confidence) / 2.0;
                    v.difference = mean;
                    v.lower = Quantile(means, tail);
                    v.upper = Quantile(means, 1.0 - tail);
                    v.pairs = differences.size();
                }
            }
            out[scene].push_back(v);
        }
    }
    return out;
}

std::string AddVdpResults(const std::vector<VdpScore>& scores, const std::vector<std::string>& variants,
                          const std::string& baseline, const std::string& displayText,
                          const std::filesystem::path& outDir, nlohmann::json& summary, HtmlReport& report) {
    const auto summarized = SummarizeVdp(scores, variants, baseline);
    WriteTextAtomically(outDir / "jod.csv", VdpCsv(scores));
    summary["fovvideovdp"] = VdpSummaryJson(summarized, displayText);
    report.tables.insert(report.tables.begin(), VdpReportTable(summarized, baseline, displayText));
    return VdpTable(summarized, baseline, displayText);
}

std::string VdpCsv(const std::vector<VdpScore>& scores) {
    std::string out = "scene,seed,eye,variant,jod,jod_sustained,jod_transient\n";
    for (const VdpScore& s : scores)
        out += fmt::format("{},{},{},{},{:.9g},{:.9g},{:.9g}\n", s.scene, s.seed, s.eye, s.variant, s.jod,
                           s.jodSustained, s.jodTransient);
    return out;
}

namespace {

std::string MethodText(const BootstrapOptions& options) {
    return fmt::format("FovVideoVDP 1.2, foveated at the true gaze of each frame; JOD per (seed, eye) sequence "
                       "(10 = no visible difference); difference to the baseline paired on (seed, eye), "
                       "{:g} % percentile bootstrap over the pairs ({} resamples)",
                       options.confidence * 100.0, options.resamples);
}

std::string Interval(const VdpVariantSummary& v) {
    if (!v.difference) return "";
    return fmt::format("{:+.3f} [{:+.3f}, {:+.3f}]", *v.difference, v.lower, v.upper);
}

}  // namespace

nlohmann::json VdpSummaryJson(const std::map<std::string, std::vector<VdpVariantSummary>>& summary,
                              const std::string& displayText, const BootstrapOptions& options) {
    nlohmann::json scenes = nlohmann::json::object();
    for (const auto& [scene, variants] : summary)
        for (const VdpVariantSummary& v : variants) {
            nlohmann::json j = {{"jod", v.jod},
                                {"jod_sustained", v.jodSustained},
                                {"jod_transient", v.jodTransient},
                                {"sequences", v.sequences}};
            if (v.difference)
                j["vs_baseline"] = {{"difference", *v.difference}, {"lower", v.lower}, {"upper", v.upper},
                                    {"pairs", v.pairs}};
            scenes[scene][v.variant] = j;
        }
    return {{"method", MethodText(options)}, {"display", displayText}, {"scenes", scenes}};
}

std::string VdpTable(const std::map<std::string, std::vector<VdpVariantSummary>>& summary,
                     const std::string& baseline, const std::string& displayText) {
    std::string out = fmt::format("FovVideoVDP JOD (foveated at the true gaze; 10 = no visible difference; {})\n",
                                  displayText);
    // The name columns as wide as the longest scene and variant names (brdf-detail-moving,
    // two-history-asvgf-stable-hysteresis).
    size_t sceneWidth = std::string_view("scene").size(), variantWidth = std::string_view("variant").size();
    for (const auto& [scene, variants] : summary) {
        sceneWidth = std::max(sceneWidth, scene.size());
        for (const VdpVariantSummary& v : variants) variantWidth = std::max(variantWidth, v.variant.size());
    }
    out += fmt::format("{:<{}} {:<{}} {:>7}  {:<28} {:>9} {:>9}\n", "scene", sceneWidth, "variant", variantWidth,
                       "JOD", fmt::format("vs {} [95% CI]", baseline), "sustained", "transient");
    for (const auto& [scene, variants] : summary)
        for (const VdpVariantSummary& v : variants)
            out += fmt::format("{:<{}} {:<{}} {:>7.3f}  {:<28} {:>9.3f} {:>9.3f}\n", scene, sceneWidth, v.variant,
                               variantWidth, v.jod, Interval(v), v.jodSustained, v.jodTransient);
    return out + "\n";
}

ReportTable VdpReportTable(const std::map<std::string, std::vector<VdpVariantSummary>>& summary,
                           const std::string& baseline, const std::string& displayText) {
    ReportTable table{fmt::format("FovVideoVDP JOD, foveated at the true gaze (10 = no visible difference; {})",
                                  displayText),
                      {"scene", "variant", "JOD", fmt::format("vs {} [95 % CI]", baseline), "sustained JOD",
                       "transient JOD", "sequences"},
                      {}};
    for (const auto& [scene, variants] : summary)
        for (const VdpVariantSummary& v : variants)
            table.rows.push_back({scene, v.variant, fmt::format("{:.3f}", v.jod), Interval(v),
                                  fmt::format("{:.3f}", v.jodSustained), fmt::format("{:.3f}", v.jodTransient),
                                  std::to_string(v.sequences)});
    return table;
}

}  // namespace fovrt
