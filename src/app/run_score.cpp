#include "app/run_score.h"

#include <cstdio>

#include <fmt/format.h>

#include "app/experiment.h"
#include "app/experiment_stats.h"
#include "app/report_summary.h"
#include "core/atomic_file.h"
#include "core/check.h"
#include "core/error.h"
#include "pipeline/metric_fovea.h"

namespace fovrt {

namespace {

std::string FirstLabel(const Scene& scene) {
    std::vector<std::string> used;
    return SceneLabel(scene.name, used);
}

}  // namespace

PassScorer::PassScorer(const RunConfig& config, const Scene& scene, std::string label, double fps,
                       Results& results, int visualFrame)
    : config_(config),
      fovea_(MetricFovea(config.foveation, config.camera.width)),
      detailInstances_(InstancesWithMaterialMaps(scene)),
      collector_(results) {
    images_.scene = std::move(label);
    if (config.metric.vdp) vdp_.emplace(config, fps, visualFrame);
}

void PassScorer::BeginEye(const StereoFrame& frame, int eye, const Plane<vec3>& reference) {
    const EyeFrame& e = frame.eyes[size_t(eye)];
    if (vdp_) vdp_->AddReference(eye, int(frame.frame), e.camera, reference, e.trueGazePixel);
    detail_ = DetailMask(detailInstances_, e.inputs);
    reference_ = &reference;
    images_.seed = config_.run.seed;
    images_.frame = int(frame.frame);
    images_.eye = eye;
    images_.camera = e.camera;
    images_.gazeEye = e.trueGazeEye;  // errors are scored where the eye was
    images_.fovea = fovea_;
    images_.cameraCut = e.inputs.cameraCut;
    images_.reference = reference_;
    images_.detailMask = &detail_;
}

void PassScorer::AddOutput(const std::string& variant, const Plane<vec3>& output) {
    FOVRT_CHECK(reference_ != nullptr);
    images_.outputs = {{variant, &output}};
    collector_.Add(images_);
    images_.outputs.clear();
    if (vdp_) vdp_->AddOutput(images_.eye, variant, output);
}

std::vector<VdpScore> PassScorer::ScoreVdp() {
    return vdp_ ? vdp_->Score(images_.scene, config_.run.seed) : std::vector<VdpScore>{};
}

RunScorer::RunScorer(const RunConfig& config, FrameLoop& loop)
    : config_(config),
      scorer_(config, loop.Pipeline().GetScene(), FirstLabel(loop.Pipeline().GetScene()),
              loop.Pipeline().FramesPerSecond(), results_) {
    FOVRT_CHECK(loop.HasReferences());
}

void RunScorer::Reference(const StereoFrame& frame, int eye, const ReferenceLookup& reference) {
    referenceRays_ += reference.rays;
    referenceHits_ += reference.cacheHit ? 1 : 0;
    ++referenceLookups_;
    scorer_.BeginEye(frame, eye, *reference.image);
}

void RunScorer::Output(const StereoFrame&, int, const DenoisedOutput& output) {
    scorer_.AddOutput(*output.name, *output.image);
}

nlohmann::json RunScorer::Finish(const std::filesystem::path& outDir, const std::string& baseline) {
    const std::vector<std::string>& variants = config_.denoise.denoisers;
    const std::string& label = scorer_.Label();
    const ExperimentStats stats(results_, baseline);
    nlohmann::json summary = SummaryJson(results_, stats);
    const std::string csv = fmt::format("frames-{}.csv", label);
    WriteFrameCsv(outDir / csv, results_, label);

    nlohmann::json block;
    block["reference"] = {{"cache_dir", config_.reference.cacheDir},
                          {"spp", config_.reference.spp},
                          {"seed", config_.reference.seed},
                          {"cache_hits", referenceHits_},
                          {"lookups", referenceLookups_},
                          {"rays", referenceRays_}};  // part of the manifest's counters.rays
    block["files"] = {csv, "summary.json"};
    nlohmann::json relMse = nlohmann::json::object();
    for (const std::string& variant : variants)
        for (const std::string& region : ComparedRegions())
            if (auto mean = results_.Mean(label, variant, region, "relmse")) relMse[variant][region] = mean->mean;
    block["relmse"] = relMse;

    std::string vdpTable;
    if (VdpExperimentScorer* vdp = scorer_.Vdp()) {
        const std::vector<VdpScore> scores = scorer_.ScoreVdp();
        const std::string display = VdpDisplayText(vdp->Display());
        const auto summarized = SummarizeVdp(scores, variants, baseline);
        WriteTextAtomically(outDir / "jod.csv", VdpCsv(scores));
        summary["fovvideovdp"] = VdpSummaryJson(summarized, display);
        vdpTable = VdpTable(summarized, baseline, display);
        block["files"].push_back("jod.csv");
        nlohmann::json jod = nlohmann::json::object();
        for (const VdpScore& s : scores) jod[s.variant][s.eye == 0 ? "left" : "right"] = s.jod;
        for (const auto& [scene, rows] : summarized)
            for (const VdpVariantSummary& v : rows) jod[v.variant]["mean"] = v.jod;
        block["fovvideovdp"] = {{"display", display}, {"jod", jod}};
    }
    WriteTextAtomically(outDir / "summary.json", summary.dump(2) + "\n");
    std::printf("%s%s", SummaryTable(results_, stats).c_str(), vdpTable.c_str());
    return block;
}

}  // namespace fovrt
