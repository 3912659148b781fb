#include "app/run_score.h"

#include <cstdio>

#include <fmt/format.h>

#include "app/experiment.h"
#include "pipeline/metric_fovea.h"
#include "app/experiment_stats.h"
#include "app/report_summary.h"
#include "core/atomic_file.h"
#include "core/check.h"
#include "core/error.h"

namespace fovrt {

namespace {

std::string FirstLabel(const Scene& scene) {
    std::vector<std::string> used;
    return SceneLabel(scene.name, used);
}

}  // namespace

RunScorer::RunScorer(const RunConfig& config, FramePipeline& pipeline)
    : config_(config),
      pipeline_(pipeline),
      cache_(config.reference.cacheDir),
      fingerprint_(SceneFingerprint(pipeline.GetScene())),
      label_(FirstLabel(pipeline.GetScene())),
      fovea_(MetricFovea(config.foveation, config.camera.width)),
      detailInstances_(InstancesWithMaterialMaps(pipeline.GetScene())),
      collector_(results_) {
    if (config.metric.vdp) vdp_.emplace(config, pipeline.FramesPerSecond());
}

void RunScorer::BeginEye(const StereoFrame& frame, int eye) {
    const EyeFrame& e = frame.eyes[size_t(eye)];
    const ReferenceKey key = MakeReferenceKey(pipeline_.GetScene(), fingerprint_, frame.frame, frame.timeSeconds, eye,
                                              e.camera, config_.reference.spp, config_.run.maxDepth,
                                              config_.reference.seed);
    bool hit = false;
    const uint64_t raysBefore = pipeline_.GetRenderer().Stats().Rays();
    reference_ = cache_.GetOrRender(key, pipeline_.GetRenderer(), &hit);
    referenceRays_ += pipeline_.GetRenderer().Stats().Rays() - raysBefore;
    referenceHits_ += hit ? 1 : 0;
    ++referenceLookups_;
    if (vdp_) vdp_->AddReference(eye, int(frame.frame), e.camera, reference_, e.trueGazePixel);
    // As the experiment's images of this eye (experiment.cpp): errors are scored where the eye was.
    detail_ = DetailMask(detailInstances_, e.inputs);
    images_ = EyeFrameImages{};
    images_.scene = label_;
    images_.seed = config_.run.seed;
    images_.frame = int(frame.frame);
    images_.eye = eye;
    images_.camera = e.camera;
    images_.gazeEye = e.trueGazeEye;
    images_.fovea = fovea_;
    images_.cameraCut = e.inputs.cameraCut;
    images_.reference = &reference_;
    images_.detailMask = &detail_;
}

void RunScorer::AddOutput(const std::string& variant, const Plane<vec3>& output) {
    FOVRT_CHECK(images_.reference != nullptr);
    EyeFrameImages one = images_;
    one.outputs = {{variant, &output}};
    collector_.Add(one);
    if (vdp_) vdp_->AddOutput(images_.eye, variant, output);
}

nlohmann::json RunScorer::Finish(const std::filesystem::path& outDir, const std::string& baseline) {
    const std::vector<std::string>& variants = config_.denoise.denoisers;
    const ExperimentStats stats(results_, baseline);
    nlohmann::json summary = SummaryJson(results_, stats);
    const std::string csv = fmt::format("frames-{}.csv", label_);
    WriteFrameCsv(outDir / csv, results_, label_);

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
            if (auto mean = results_.Mean(label_, variant, region, "relmse")) relMse[variant][region] = mean->mean;
    block["relmse"] = relMse;

    std::string vdpTable;
    if (vdp_) {
        const std::vector<VdpScore> scores = vdp_->Score(label_, config_.run.seed);
        const std::string display = VdpDisplayText(vdp_->Display());
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
