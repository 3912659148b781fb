// Scoring a pass over the frames (one scene, one run seed) against the references, with the same
// code in `fovrt run --score` and `fovrt experiment`:
// - PassScorer: per eye and frame, MetricsCollector (relMSE, SSIM, FLIP, temporal error per region,
//   fovea at the true gaze) on every variant's output, and VdpExperimentScorer per eye sequence
//   (FovVideoVDP JOD, foveated at the true gaze of each frame).
// - RunScorer: `fovrt run` with run.score (or --score), a FrameLoopObserver over one PassScorer
//   that writes, named and laid out as the experiment's, frames-<scene>.csv, jod.csv,
//   summary.json, and returns a "score" block for the manifest. Same config, seed and variants ⇒
//   the experiment's numbers.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/experiment_vdp.h"
#include "app/report.h"
#include "app/report_collect.h"
#include "loop/frame_loop.h"

namespace fovrt {

class PassScorer {
public:
    // Rows go to `results` under scene label `label` and the config's run.seed; `visualFrame`: the
    // frame whose FovVideoVDP difference map is kept (-1: none).
    PassScorer(const RunConfig& config, const Scene& scene, std::string label, double fps, Results& results,
               int visualFrame = -1);

    // One eye of `frame`: its reference (errors are scored where the eye really was).
    void BeginEye(const StereoFrame& frame, int eye, const Plane<vec3>& reference);
    // A variant's output for that eye.
    void AddOutput(const std::string& variant, const Plane<vec3>& output);
    // FovVideoVDP of every (eye, variant) sequence (empty with metric.vdp off).
    std::vector<VdpScore> ScoreVdp();
    VdpExperimentScorer* Vdp() { return vdp_ ? &*vdp_ : nullptr; }
    const std::string& Label() const { return images_.scene; }

private:
    const RunConfig& config_;
    FoveaRadius fovea_;
    std::vector<uint8_t> detailInstances_;
    MetricsCollector collector_;
    std::optional<VdpExperimentScorer> vdp_;
    EyeFrameImages images_;  // the eye being scored
    const Plane<vec3>* reference_ = nullptr;
    Plane<uint8_t> detail_;
};

class RunScorer : public FrameLoopObserver {
public:
    // `loop`: the run's (references on); its scene names the rows.
    RunScorer(const RunConfig& config, FrameLoop& loop);

    void Reference(const StereoFrame& frame, int eye, const ReferenceLookup& reference) override;
    void Output(const StereoFrame& frame, int eye, const DenoisedOutput& output) override;

    // Scores the eye sequences, writes the CSVs and summary.json under `outDir`, prints the
    // tables on stdout and returns the manifest's "score" block.
    nlohmann::json Finish(const std::filesystem::path& outDir, const std::string& baseline);

private:
    const RunConfig& config_;
    Results results_;
    PassScorer scorer_;
    int referenceHits_ = 0, referenceLookups_ = 0;
    uint64_t referenceRays_ = 0;  // traced for references missing from the cache
};

}  // namespace fovrt
