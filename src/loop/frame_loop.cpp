#include "loop/frame_loop.h"

#include <algorithm>
#include <chrono>

#include "core/cpu_time.h"
#include "core/interrupt.h"

namespace fovrt {
bool SeedWork::RunsEye(int eye) const {
    if (runs.empty()) return true;
    return std::any_of(runs.begin(), runs.end(), [&](const std::array<bool, 2>& r) { return r[size_t(eye)]; });
}

bool SeedWork::Runs(size_t variant, int eye) const {
    return runs.empty() || (variant < runs.size() && runs[variant][size_t(eye)]);
}

FrameLoop::FrameLoop(const RunConfig& config, bool references, const RunConfig* pipelineConfig)
    : config_(config),
      pipeline_(pipelineConfig ? *pipelineConfig : config),
      denoisers_(RunDenoiseConfig(config)),
      outputs_(denoisers_.size()) {
    if (references) {
        cache_.emplace(config.reference.cacheDir);
        fingerprint_ = fovrt::SceneFingerprint(pipeline_.GetScene());
    }
}

void FrameLoop::Detach(FrameLoopObserver& observer) {
    observers_.erase(std::remove(observers_.begin(), observers_.end(), &observer), observers_.end());
}

void FrameLoop::RunSeed(size_t seedIndex, const SeedWork& work, const std::function<bool(FrameRequest&)>& next) {
    // The first pass with the config's own seed runs on the pipeline as built; every other one
    // restarts it (same scene and BVH), as a fresh pipeline with that seed would start.
    if (!fresh_ || work.seed != config_.run.seed) pipeline_.Restart(work.seed);
    fresh_ = false;
    config_.run.seed = work.seed;
    denoisers_.Reset();
    for (FrameLoopObserver* o : observers_) o->BeginSeed(seedIndex, work.seed, pipeline_);

    FrameRequest request;
    StereoFrame frame;
    Plane<vec3> reference;
    while (next(request)) {
        ThrowIfInterrupted();
        pipeline_.Render(request, frame);
        if (request.frame < uint32_t(config_.run.firstFrame)) {
            WarmUp(work, frame);
            continue;
        }
        for (FrameLoopObserver* o : observers_) o->Frame(frame);
        for (int eye = 0; eye < 2; ++eye) {
            if (!work.RunsEye(eye)) continue;
            for (FrameLoopObserver* o : observers_) o->Eye(frame, eye);
            if (cache_) {
                const EyeFrame& e = frame.eyes[size_t(eye)];
                const auto start = std::chrono::steady_clock::now();
                const uint64_t raysBefore = pipeline_.GetRenderer().Stats().Rays();
                const ReferenceKey key = MakeReferenceKey(pipeline_.GetScene(), fingerprint_, frame.frame,
                                                          frame.timeSeconds, eye, e.camera, config_.reference.spp,
                                                          config_.run.maxDepth, config_.reference.seed);
                ReferenceLookup lookup;
                reference = cache_->GetOrRender(key, pipeline_.GetRenderer(), &lookup.cacheHit);
                lookup.image = &reference;
                lookup.rays = pipeline_.GetRenderer().Stats().Rays() - raysBefore;
                lookup.ms = MsSince(start);
                for (FrameLoopObserver* o : observers_) o->Reference(frame, eye, lookup);
            }
            for (size_t v = 0; v < denoisers_.size(); ++v) {
                if (!work.Runs(v, eye)) continue;
                DenoisedOutput output;
                output.variant = v;
                output.name = &denoisers_.Name(v);
                output.denoiser = &denoisers_.At(v, eye);
                const auto start = std::chrono::steady_clock::now();
                output.denoiser->Denoise(frame.eyes[size_t(eye)].inputs, outputs_[v]);
                output.wallMs = MsSince(start);
                output.image = &outputs_[v];
                for (FrameLoopObserver* o : observers_) o->Output(frame, eye, output);
            }
        }
        for (FrameLoopObserver* o : observers_) o->EndFrame(frame);
    }
    for (FrameLoopObserver* o : observers_) o->EndSeed(pipeline_);
}

void FrameLoop::WarmUp(const SeedWork& work, StereoFrame& frame) {
    for (int eye = 0; eye < 2; ++eye)
        for (size_t v = 0; v < denoisers_.size(); ++v)
            if (work.Runs(v, eye)) denoisers_.At(v, eye).Denoise(frame.eyes[size_t(eye)].inputs, outputs_[v]);
}

}  // namespace fovrt
