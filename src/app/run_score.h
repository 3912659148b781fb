// RunScorer: `fovrt run` with run.score (or --score) scores every variant's output against the
// reference `fovrt experiment` would use for the same frame and eye (app/reference_cache.h, the
// same key: read from reference.cache_dir, rendered and stored there when missing), with the
// experiment's own code: MetricsCollector per frame (relMSE, SSIM, FLIP, temporal error per
// region, fovea at the true gaze) and VdpExperimentScorer per eye sequence (FovVideoVDP JOD,
// foveated at the true gaze of each frame). Same config, seed and variants ⇒ the experiment's
// numbers. Outputs in the run's folder, named and laid out as the experiment's: the per-frame CSV
// frames-<scene>.csv, jod.csv, summary.json, and a "score" block for the manifest.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/experiment_vdp.h"
#include "pipeline/frame_pipeline.h"
#include "pipeline/reference_cache.h"
#include "app/report.h"
#include "app/report_collect.h"

namespace fovrt {

class RunScorer {
public:
    // `pipeline`: the run's (its renderer renders missing references at the current frame).
    RunScorer(const RunConfig& config, FramePipeline& pipeline);

    // One eye of the frame `pipeline` just rendered: its reference (cached or rendered now).
    void BeginEye(const StereoFrame& frame, int eye);
    // A variant's output for that eye (call once per variant, in the run's order).
    void AddOutput(const std::string& variant, const Plane<vec3>& output);

    // Scores the eye sequences, writes the CSVs and summary.json under `outDir`, prints the
    // tables on stdout and returns the manifest's "score" block.
    nlohmann::json Finish(const std::filesystem::path& outDir, const std::string& baseline);

private:
    const RunConfig& config_;
    FramePipeline& pipeline_;
    ReferenceCache cache_;
    uint64_t fingerprint_;
    std::string label_;
    FoveaRadius fovea_;
    std::vector<uint8_t> detailInstances_;
    Results results_;
    MetricsCollector collector_;
    std::optional<VdpExperimentScorer> vdp_;
    int referenceHits_ = 0, referenceLookups_ = 0;
    uint64_t referenceRays_ = 0;  // traced for references missing from the cache
    // The eye being scored.
    EyeFrameImages images_;
    Plane<vec3> reference_;
    Plane<uint8_t> detail_;
};

}  // namespace fovrt
