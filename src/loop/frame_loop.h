// FrameLoop: the render → reference → denoise loop below every headless command. One FrameLoop
// per scene: it loads the scene and builds its BVH once (FramePipeline), compiles the denoisers'
// pipelines once (DenoiserSet), and runs one pass over the frames per run seed, each as a separate
// run with that seed would (the renderer and the gaze restart, every history is dropped). What a
// command does with the frames — scoring them, report visuals, timings, frames.jsonl, EXR and PNG
// files — attaches as FrameLoopObserver; the loop itself writes nothing.
//
// A warm-up frame (run.warmup_frames: before run.first_frame) is rendered and denoised, so the
// histories advance, and nothing else: no reference, no observer sees it.
//
// One frame, in the order observers see it:
//   Frame(frame)                       both eyes rendered (FramePipeline::Render)
//   for each eye the pass runs:
//     Eye(frame, eye)                  before the eye's reference and denoisers (write inputs)
//     Reference(frame, eye, ref, ...)  with references on: the cached (or freshly rendered) image
//     Output(frame, eye, variant, ...) each denoiser the pass runs on this eye, in the set's order
//   EndFrame(frame)
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "config/config.h"
#include "core/image.h"
#include "denoise/denoiser.h"
#include "pipeline/denoiser_set.h"
#include "pipeline/frame_pipeline.h"
#include "pipeline/reference_cache.h"

namespace fovrt {

// One eye's reference as the loop looked it up.
struct ReferenceLookup {
    const Plane<vec3>* image = nullptr;
    bool cacheHit = false;
    double ms = 0.0;        // lookup, or rendering and storing it when it was missing
    uint64_t rays = 0;      // traced for it (0 on a cache hit)
};

// One denoiser's output for one eye.
struct DenoisedOutput {
    size_t variant = 0;           // index in the loop's DenoiserSet
    const std::string* name = nullptr;
    const Plane<vec3>* image = nullptr;
    Denoiser* denoiser = nullptr;  // its timings, debug views and counters of this frame
    double wallMs = 0.0;           // Denoise() as the host saw it
};

class FrameLoopObserver {
public:
    virtual ~FrameLoopObserver() = default;
    // A pass over the frames with run seed `seed` begins; `pipeline` has restarted with it.
    virtual void BeginSeed(size_t /*seedIndex*/, uint32_t /*seed*/, FramePipeline& /*pipeline*/) {}
    virtual void Frame(const StereoFrame& /*frame*/) {}
    virtual void Eye(const StereoFrame& /*frame*/, int /*eye*/) {}
    virtual void Reference(const StereoFrame& /*frame*/, int /*eye*/, const ReferenceLookup& /*reference*/) {}
    virtual void Output(const StereoFrame& /*frame*/, int /*eye*/, const DenoisedOutput& /*output*/) {}
    virtual void EndFrame(const StereoFrame& /*frame*/) {}
    // The pass is over (not called when it was interrupted).
    virtual void EndSeed(FramePipeline& /*pipeline*/) {}
};

// Which work of one seed's pass to do: every eye and variant, or a shard's share of them.
struct SeedWork {
    uint32_t seed = 1;
    // runs[variant][eye]: the denoiser runs on the eye; an eye no variant runs on is skipped whole
    // (no reference either). Empty: every variant on both eyes.
    std::vector<std::array<bool, 2>> runs;

    bool RunsEye(int eye) const;
    bool Runs(size_t variant, int eye) const;
};

class FrameLoop {
public:
    // `config`: scene, camera, foveation, gaze and run.seed of the first pass; its
    // denoise.denoisers are the loop's variants. `references`: every eye a pass runs gets its
    // reference from reference.cache_dir (reference.spp, reference.seed; rendered and stored when
    // missing). `pipelineConfig`: what the FramePipeline is built from when it differs (a replay's
    // gaze source, app/replay.h); default `config`.
    FrameLoop(const RunConfig& config, bool references, const RunConfig* pipelineConfig = nullptr);

    FramePipeline& Pipeline() { return pipeline_; }
    DenoiserSet& Denoisers() { return denoisers_; }
    const RunConfig& Config() const { return config_; }
    bool HasReferences() const { return cache_.has_value(); }
    uint64_t SceneFingerprint() const { return fingerprint_; }

    // Observers are called in the order they were added; the loop does not own them.
    void Attach(FrameLoopObserver& observer) { observers_.push_back(&observer); }
    void Detach(FrameLoopObserver& observer);

    // Before the first pass: restarts the pipeline with `work.seed` (unless it is the first pass
    // with the config's own seed) and drops every denoiser history. Then renders each frame
    // `next` gives, until it returns false. `seedIndex` names the pass to the observers.
    // An interrupt (core/interrupt.h) ends it with Interrupted between frames.
    void RunSeed(size_t seedIndex, const SeedWork& work, const std::function<bool(FrameRequest&)>& next);

private:
    // A frame before run.first_frame: each denoiser the pass runs advances its histories.
    void WarmUp(const SeedWork& work, StereoFrame& frame);

    RunConfig config_;
    FramePipeline pipeline_;
    DenoiserSet denoisers_;
    std::optional<ReferenceCache> cache_;
    uint64_t fingerprint_ = 0;
    bool fresh_ = true;  // no pass has run: the pipeline is as built
    std::vector<FrameLoopObserver*> observers_;
    std::vector<Plane<vec3>> outputs_;  // one per variant, reused frame to frame
};

}  // namespace fovrt
