#include "app/experiment_pass.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "core/cpu_time.h"
#include "gaze/tracker.h"
#include "io/exr.h"
#include "pipeline/metric_fovea.h"

namespace fovrt {
namespace {


// Blink, and the gaze's angular speed since the previous valid sample (head space), for the
// report's per-frame plots.
GazeMark GazeMarkOf(int frame, const GazeSample& gaze, const std::optional<GazeSample>& previous) {
    GazeMark mark;
    mark.frame = frame;
    mark.blink = !gaze.valid;
    if (gaze.valid) {
        const vec2 angles = GazeAnglesFromDirection(gaze.direction);
        mark.yawDeg = angles.x, mark.pitchDeg = angles.y;
    }
    if (gaze.valid && previous && previous->valid && gaze.timeSeconds > previous->timeSeconds) {
        const double cosine = std::clamp(double(glm::dot(glm::normalize(gaze.direction),
                                                         glm::normalize(previous->direction))), -1.0, 1.0);
        mark.speedDegPerSecond = std::acos(cosine) * 180.0 / 3.14159265358979 /
                                 (gaze.timeSeconds - previous->timeSeconds);
    }
    return mark;
}

}  // namespace

ExperimentScoring::ExperimentScoring(const RunConfig& config, SceneRecord& record, ExperimentPart& part,
                                     int visualFrame)
    : config_(config), record_(record), part_(part), visualFrame_(visualFrame) {}

void ExperimentScoring::BeginSeed(size_t, uint32_t seed, FramePipeline& pipeline) {
    scorer_.reset();  // it holds passConfig_
    passConfig_ = config_;
    passConfig_.run.seed = seed;
    scorer_.emplace(passConfig_, pipeline.GetScene(), record_.label, pipeline.FramesPerSecond(), part_.results,
                    visualsHere_ ? visualFrame_ : -1);
}

void ExperimentScoring::Reference(const StereoFrame& frame, int eye, const ReferenceLookup& reference) {
    record_.referenceHits += reference.cacheHit ? 1 : 0;
    ++record_.referenceLookups;
    ++record_.eyeFrames;
    record_.times.referenceMs += reference.ms;
    const auto start = std::chrono::steady_clock::now();
    scorer_->BeginEye(frame, eye, *reference.image);
    record_.times.metricMs += MsSince(start);
}

void ExperimentScoring::Output(const StereoFrame&, int, const DenoisedOutput& output) {
    const auto start = std::chrono::steady_clock::now();
    scorer_->AddOutput(*output.name, *output.image);
    record_.times.metricMs += MsSince(start);
}

void ExperimentScoring::EndSeed(FramePipeline&) {
    VdpExperimentScorer* vdp = scorer_->Vdp();
    if (!vdp) return;
    const auto start = std::chrono::steady_clock::now();
    for (VdpScore& score : scorer_->ScoreVdp()) part_.vdp.push_back(std::move(score));
    record_.times.metricMs += MsSince(start);
    part_.vdpDisplay = VdpDisplayText(vdp->Display());
    if (visualsHere_) record_.visuals.vdpMaps = vdp->DiffMaps(record_.visuals.eye);
}

ReportVisuals::ReportVisuals(const RunConfig& config, FrameLoop& loop, SceneRecord& record, int visualFrame)
    : config_(config), loop_(loop), record_(record), visualFrame_(visualFrame) {}

void ReportVisuals::BeginSeed(size_t, uint32_t seed, FramePipeline& pipeline) {
    previousGaze_.reset();
    if (!here_) return;
    SceneVisuals& visuals = record_.visuals;
    record_.hasVisuals = true;
    visuals.scene = record_.label;
    visuals.width = config_.camera.width;
    visuals.height = config_.camera.height;
    visuals.eye = 0;
    visuals.seed = seed;
    visuals.foveaRadiusPixels =
        MetricFovea(config_.foveation, config_.camera.width).RadiusPixels(pipeline.RigAt(0).Eye(0));
    visuals.exposure = config_.output.exposure;
}

void ReportVisuals::Frame(const StereoFrame& frame) {
    if (!firstSeed_) return;
    record_.blinkFrames += frame.gaze.valid ? 0 : 1;
    if (here_) {
        SceneVisuals& visuals = record_.visuals;
        GazeMark mark = GazeMarkOf(int(frame.frame), frame.trueGaze, previousGaze_);
        // The rendered fovea (tracked gaze) against the true gaze, on the report's eye; a blink
        // rendered uniform has no fovea.
        const EyeFrame& shown = frame.eyes[size_t(visuals.eye)];
        mark.timeSeconds = frame.timeSeconds;
        mark.foveaDistanceDeg = AngleBetweenDeg(frame.gaze.direction, frame.trueGaze.direction);
        mark.outsideFovea = shown.uniformForBlink ||
                            glm::length(shown.gazePixel - shown.trueGazePixel) > visuals.foveaRadiusPixels;
        mark.gazeHeld = loop_.Pipeline().GazeHeld(frame.frame);
        visuals.gazeMarks.push_back(mark);
    }
    previousGaze_ = frame.trueGaze;
}

void ReportVisuals::Reference(const StereoFrame& frame, int eye, const ReferenceLookup& reference) {
    SceneVisuals& visuals = record_.visuals;
    if (!here_ || eye != visuals.eye || int(frame.frame) != visualFrame_) return;
    const EyeFrame& e = frame.eyes[size_t(eye)];
    visuals.frame = int(frame.frame);
    visuals.gazePixel = e.trueGazePixel;
    visuals.sppMap = e.sppMap;
    visuals.reference = *reference.image;
    visuals.noisy = e.inputs.NoisyImage();
    visuals.variants.clear();
}

void ReportVisuals::Output(const StereoFrame& frame, int eye, const DenoisedOutput& output) {
    if (here_ && eye == record_.visuals.eye && int(frame.frame) == visualFrame_)
        record_.visuals.variants.emplace_back(*output.name, *output.image);
}

void ReportVisuals::EndFrame(const StereoFrame& frame) {
    if (here_) record_.visuals.gazePath.push_back(frame.eyes[size_t(record_.visuals.eye)].trueGazePixel);
}

void ExperimentExr::Output(const StereoFrame& frame, int eye, const DenoisedOutput& output) {
    WriteRgbExr(dir_ / *output.name /
                    fmt::format("{}f{:05d}_{}.exr", seedInName_ ? fmt::format("s{}_", seed_) : "", frame.frame,
                                eye == 0 ? "left" : "right"),
                *output.image);
}

TracedSamples::TracedSamples(const RunConfig& config, SceneRecord& record)
    : fovea_(MetricFovea(config.foveation, config.camera.width)), record_(record) {}

void TracedSamples::Eye(const StereoFrame& frame, int eye) {
    if (!counted_[size_t(eye)]) return;
    const EyeFrame& e = frame.eyes[size_t(eye)];
    const RegionSet regions = RegionSet::Build(e.camera, e.trueGazeEye, fovea_, {});
    const Plane<uint16_t>& samples = e.inputs.sampleCount;
    for (size_t r = 0; r < kTracedRegions.size(); ++r) {
        const Region* region = regions.Find(kTracedRegions[r]);
        if (!region) continue;  // an empty fovea (the gaze off the image) or periphery
        uint64_t sum = 0, guides = 0;
        for (size_t p = 0; p < samples.size(); ++p)
            if (region->mask[p]) sum += samples[p], guides += samples[p] == 0;
        record_.tracedSamples[r] += sum;
        record_.guidePixels[r] += guides;
        record_.tracedPixels[r] += region->pixelCount;
    }
}

double TracedSamples::GuideRaysPerPixel(const SceneRecord& record, size_t region) {
    return record.tracedPixels[region] ? double(record.guidePixels[region]) / double(record.tracedPixels[region]) : 0.0;
}

double TracedSamples::SamplesPerPixel(const SceneRecord& record, size_t region) {
    return record.tracedPixels[region] ? double(record.tracedSamples[region]) / double(record.tracedPixels[region]) : 0.0;
}

void PassCosts::Eye(const StereoFrame& frame, int eye) { record_.times.renderMs += frame.eyes[size_t(eye)].renderMs; }

void PassCosts::Output(const StereoFrame&, int, const DenoisedOutput& output) {
    record_.times.denoiseMs += output.wallMs;
    for (const PassTiming& t : output.denoiser->LastTimings()) part_.timings.Add(*output.name, t.pass, t.ms);
}

void PassCosts::EndFrame(const StereoFrame& frame) {
    progress_.Step(manySeeds_ ? fmt::format("{} seed {} frame {}", record_.label, seed_, frame.frame)
                              : fmt::format("{} frame {}", record_.label, frame.frame));
}

void PassCosts::EndSeed(FramePipeline& pipeline) {
    const RenderStats stats = pipeline.GetRenderer().Stats();
    record_.rays += stats.Rays();
    record_.droppedSamples += stats.droppedSamples;
}

}  // namespace fovrt
