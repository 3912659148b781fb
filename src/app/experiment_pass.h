// What `fovrt experiment` attaches to the frame loop (loop/frame_loop.h) for one scene: each a
// FrameLoopObserver with one job, filling the scene's record and the part's results.
// - ExperimentScoring: every owned eye and variant scored against its reference (PassScorer, the
//   same code as `run --score`), FovVideoVDP per pass, the reference cache's counts.
// - ReportVisuals: the report's images of one eye and frame under the first seed, its gaze marks.
// - ExperimentExr: each variant's output as EXR (output.write_exr).
// - PassCosts: per-pass denoiser timings, wall times, rays and dropped samples, progress.
// - TracedSamples: the path samples the tracer took per pixel, by region at the true gaze (the
//   measured sampling, not the nominal spp map).
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/experiment_shards.h"
#include "app/progress.h"
#include "app/run_score.h"
#include "loop/frame_loop.h"

namespace fovrt {

class ExperimentScoring : public FrameLoopObserver {
public:
    // `visuals`: the record's report images (their VDP difference maps); `visualFrame` the frame
    // whose maps are kept on the passes that show visuals (ReportVisuals::ShownIn).
    ExperimentScoring(const RunConfig& config, SceneRecord& record, ExperimentPart& part, int visualFrame);

    void BeginSeed(size_t seedIndex, uint32_t seed, FramePipeline& pipeline) override;
    void Reference(const StereoFrame& frame, int eye, const ReferenceLookup& reference) override;
    void Output(const StereoFrame& frame, int eye, const DenoisedOutput& output) override;
    void EndSeed(FramePipeline& pipeline) override;
    // The pass shows the report's images (its VDP keeps the visual frame's difference maps).
    void SetVisualsHere(bool here) { visualsHere_ = here; }

private:
    const RunConfig& config_;
    SceneRecord& record_;
    ExperimentPart& part_;
    int visualFrame_;
    bool visualsHere_ = false;
    RunConfig passConfig_;  // the config with this pass's run seed
    std::optional<PassScorer> scorer_;
};

class ReportVisuals : public FrameLoopObserver {
public:
    ReportVisuals(const RunConfig& config, FrameLoop& loop, SceneRecord& record, int visualFrame);

    // Whether the pass of `seedIndex` over `eyes` shows the report's images (eye 0, first seed).
    static bool ShownIn(size_t seedIndex, const SeedWork& work) { return seedIndex == 0 && work.RunsEye(0); }
    void Prepare(size_t seedIndex, const SeedWork& work) {
        firstSeed_ = seedIndex == 0;
        here_ = ShownIn(seedIndex, work);
    }

    void BeginSeed(size_t seedIndex, uint32_t seed, FramePipeline& pipeline) override;
    void Frame(const StereoFrame& frame) override;
    void Reference(const StereoFrame& frame, int eye, const ReferenceLookup& reference) override;
    void Output(const StereoFrame& frame, int eye, const DenoisedOutput& output) override;
    void EndFrame(const StereoFrame& frame) override;

private:
    const RunConfig& config_;
    FrameLoop& loop_;
    SceneRecord& record_;
    int visualFrame_;
    bool firstSeed_ = false, here_ = false;
    std::optional<GazeSample> previousGaze_;
};

class ExperimentExr : public FrameLoopObserver {
public:
    ExperimentExr(std::filesystem::path sceneDir, bool seedInName) : dir_(std::move(sceneDir)), seedInName_(seedInName) {}
    void BeginSeed(size_t, uint32_t seed, FramePipeline&) override { seed_ = seed; }
    void Output(const StereoFrame& frame, int eye, const DenoisedOutput& output) override;

private:
    std::filesystem::path dir_;
    bool seedInName_;
    uint32_t seed_ = 0;
};

// The regions the measured sampling is reported in, in SceneRecord::tracedSamples' order.
inline constexpr std::array<const char*, 3> kTracedRegions = {"whole", "fovea", "periphery"};

class TracedSamples : public FrameLoopObserver {
public:
    TracedSamples(const RunConfig& config, SceneRecord& record);
    // The eyes this pass counts: each (scene, seed, eye) is counted by exactly one part of a
    // sharded experiment (the one that runs its first variant), so merged shards sum to the
    // single run's counts.
    void CountEyes(std::array<bool, 2> eyes) { counted_ = eyes; }
    void Eye(const StereoFrame& frame, int eye) override;
    // Samples per pixel of region i of kTracedRegions; 0 where no pixel was counted.
    static double SamplesPerPixel(const SceneRecord& record, size_t region);
    // Guide rays per pixel of region i: the pixels without a path sample, which get only their
    // primary hit (normal, depth, motion, albedo; a headset renderer rasterizes these).
    static double GuideRaysPerPixel(const SceneRecord& record, size_t region);

private:
    FoveaRadius fovea_;
    SceneRecord& record_;
    std::array<bool, 2> counted_{true, true};
};

class PassCosts : public FrameLoopObserver {
public:
    PassCosts(SceneRecord& record, ExperimentPart& part, Progress& progress, bool manySeeds)
        : record_(record), part_(part), progress_(progress), manySeeds_(manySeeds) {}
    void BeginSeed(size_t, uint32_t seed, FramePipeline&) override { seed_ = seed; }
    void Eye(const StereoFrame& frame, int eye) override;
    void Output(const StereoFrame& frame, int eye, const DenoisedOutput& output) override;
    void EndFrame(const StereoFrame& frame) override;
    void EndSeed(FramePipeline& pipeline) override;

private:
    SceneRecord& record_;
    ExperimentPart& part_;
    Progress& progress_;
    bool manySeeds_;
    uint32_t seed_ = 0;
};

}  // namespace fovrt
