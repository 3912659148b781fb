// FovVideoVDP (metrics/fovvideovdp.h) in `fovrt experiment`: every variant's denoised sequence
// against the reference, one JOD per (scene, seed, eye, variant) sequence, foveated at the true
// gaze of each frame (where the eye looked; the same centre as the other metrics' fovea).
//
// Display: pipeline/metric_display.h.
// Statistics: per variant the mean JOD (and of each temporal channel alone) over seeds and eyes,
// and against the baseline the mean paired difference (pairs on seed and eye) with a percentile
// bootstrap interval over the pairs (metrics/statistics.h, fixed RNG seed).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/config.h"
#include "pipeline/metric_display.h"
#include "app/report_html.h"
#include "core/camera.h"
#include "core/image.h"
#include "metrics/fovvideovdp.h"
#include "metrics/statistics.h"

namespace fovrt {

// One scored sequence.
struct VdpScore {
    std::string scene;
    uint32_t seed = 1;
    int eye = 0;
    std::string variant;
    double jod = 10.0, jodSustained = 10.0, jodTransient = 10.0;
};

// Collects one (scene, seed) pass and scores its sequences at the end.
class VdpExperimentScorer {
public:
    // `fps`: the sequence's frame rate; `visualFrame`: the frame whose difference map is kept
    // (-1: none).
    VdpExperimentScorer(const RunConfig& config, double fps, int visualFrame = -1);

    // One eye's frame `frame`: the reference and where the eye really looked.
    void AddReference(int eye, int frame, const EyeCamera& camera, const Plane<vec3>& reference,
                      const vec2& trueGazePixel);
    // A variant's output for the eye's latest AddReference.
    void AddOutput(int eye, const std::string& variant, const Plane<vec3>& output);

    // Scores every (eye, variant) sequence, in eye then first-seen variant order.
    std::vector<VdpScore> Score(const std::string& scene, uint32_t seed);
    // After Score: the difference map of `visualFrame` per variant for `eye` (JOD lost per pixel).
    const std::map<std::string, Plane<float>>& DiffMaps(int eye) const { return maps_[size_t(eye)]; }
    // The display of the eyes scored (valid after the first AddReference).
    const VdpExperimentDisplay& Display() const { return display_; }

private:
    struct EyeSequences {
        std::optional<EyeCamera> camera;
        std::vector<Plane<float>> reference;
        std::vector<VdpFixation> fixations;
        int visualPosition = -1;  // position of visualFrame in the sequence
        std::vector<std::pair<std::string, std::vector<Plane<float>>>> variants;
    };
    const RunConfig& config_;
    double fps_;
    int visualFrame_;
    VdpExperimentDisplay display_;
    EyeSequences eyes_[2];
    std::map<std::string, Plane<float>> maps_[2];
};

// Per scene and variant, over seeds and eyes.
struct VdpVariantSummary {
    std::string variant;
    size_t sequences = 0;
    double jod = 0.0, jodSustained = 0.0, jodTransient = 0.0;  // means
    // Against the baseline (not for the baseline itself): mean paired JOD difference and its
    // bootstrap interval, over `pairs` (seed, eye) pairs.
    std::optional<double> difference;
    double lower = 0.0, upper = 0.0;
    size_t pairs = 0;
};
std::map<std::string, std::vector<VdpVariantSummary>> SummarizeVdp(const std::vector<VdpScore>& scores,
                                                                   const std::vector<std::string>& variants,
                                                                   const std::string& baseline,
                                                                   const BootstrapOptions& options = {});

// The experiment's outputs of the scores: jod.csv under `outDir`, summary["fovvideovdp"], the
// report's table and difference maps; returns the stdout block.
std::string AddVdpResults(const std::vector<VdpScore>& scores, const std::vector<std::string>& variants,
                          const std::string& baseline, const std::string& displayText,
                          const std::filesystem::path& outDir, nlohmann::json& summary, HtmlReport& report);

// Outputs: the per-sequence CSV (scene,seed,eye,variant,jod,jod_sustained,jod_transient), the
// summary.json block, the stdout block and the report's table.
std::string VdpCsv(const std::vector<VdpScore>& scores);
nlohmann::json VdpSummaryJson(const std::map<std::string, std::vector<VdpVariantSummary>>& summary,
                              const std::string& displayText, const BootstrapOptions& options = {});
std::string VdpTable(const std::map<std::string, std::vector<VdpVariantSummary>>& summary,
                     const std::string& baseline, const std::string& displayText);
ReportTable VdpReportTable(const std::map<std::string, std::vector<VdpVariantSummary>>& summary,
                           const std::string& baseline, const std::string& displayText);
// "camera, 17.6 px/deg, 100 cd/m²": the display in words.
std::string VdpDisplayText(const VdpExperimentDisplay& display);

}  // namespace fovrt
