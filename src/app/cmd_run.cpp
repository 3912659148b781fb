// `fovrt run`: the headless job. Renders N frames of both eyes with the configured gaze source
// and spp model (or, with --replay, a session recording's frames: app/replay.h), writes per frame
// and eye a multi-layer EXR with every FrameInputs channel, the renderer's visibility buffer and
// the spp map, denoises with every configured variant, appends one line per frame to frames.jsonl
// (gaze, samples, per-stage timings) and finishes with a run manifest (JSON: the fully resolved
// config, versions, seed, counters, timing aggregates). Memory stays flat however many frames:
// nothing per frame is kept (but, with run.score, the metric's luminance frames). The manifest is
// written last: a directory without manifest.json is an interrupted run. --record FILE writes the
// rendered frames as a session recording. run.score (--score) scores every variant against the
// cached references as `experiment` does (app/run_score.h).
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <new>
#include <optional>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/shared_options.h"
#include "app/output_dir.h"
#include "app/progress.h"
#include "app/replay.h"
#include "app/run_score.h"
#include "config/config.h"
#include "config/config_cli.h"
#include "config/config_io.h"
#include "core/atomic_file.h"
#include "core/cpu_time.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "denoise/memory_plan.h"
#include "io/exr.h"
#include "io/png.h"
#include "pipeline/build_info.h"
#include "pipeline/denoiser_set.h"
#include "pipeline/frame_pipeline.h"
#include "loop/frame_loop.h"
#include "render/visibility_buffer.h"

namespace fovrt {
namespace {

const char* kEyeNames[2] = {"left", "right"};

// Every debug view the denoiser offers of its last frame (denoise/debug_views.h), one layer each
// named as the view, in one EXR: the per-pixel state behind its output (output.write_debug_views).
void WriteDebugViewsExr(const std::filesystem::path& path, Denoiser& denoiser) {
    const std::vector<std::string> names = denoiser.DebugViews();
    if (names.empty()) return;
    std::vector<Plane<float>> planes(names.size());
    std::vector<ExrLayer> layers;
    for (size_t i = 0; i < names.size(); ++i) {
        if (!denoiser.ReadDebugView(names[i], planes[i]))
            Fail("{}: debug view {} could not be read", denoiser.Name(), names[i]);
        layers.push_back(ExrLayer::FromPlane(names[i], planes[i]));
    }
    std::filesystem::create_directories(path.parent_path());
    WriteExrLayers(path, planes[0].width(), planes[0].height(), layers);
}



// Mean, min and max of one timing over a run: what the manifest keeps of the per-frame timings
// (each frame's own are in frames.jsonl), so the manifest's size does not grow with the run.
class TimingStats {
public:
    // `key`: the path of the entry in the JSON ({"denoise", "svgf", "wall"}).
    void Add(const std::vector<std::string>& key, double ms) {
        Stat& s = stats_[key];
        s.sum += ms;
        s.min = s.count == 0 ? ms : std::min(s.min, ms);
        s.max = s.count == 0 ? ms : std::max(s.max, ms);
        ++s.count;
    }
    // Nested objects along each key, ending in {"mean", "min", "max", "count"}.
    nlohmann::json ToJson() const {
        nlohmann::json out = nlohmann::json::object();
        for (const auto& [key, s] : stats_) {
            nlohmann::json* node = &out;
            for (const std::string& part : key) node = &(*node)[part];
            *node = {{"mean", s.sum / double(s.count)}, {"min", s.min}, {"max", s.max}, {"count", s.count}};
        }
        return out;
    }

private:
    struct Stat {
        double sum = 0.0, min = 0.0, max = 0.0;
        uint64_t count = 0;
    };
    std::map<std::vector<std::string>, Stat> stats_;
};

// frames.jsonl: one JSON line per frame, written (and flushed) as the frame completes.
class FrameLog {
public:
    explicit FrameLog(const std::filesystem::path& path) : path_(path), file_(std::fopen(path.c_str(), "wb")) {
        if (!file_) Fail("cannot create '{}': {}", path.string(), std::strerror(errno));
    }
    ~FrameLog() {
        if (file_) std::fclose(file_);
    }
    FrameLog(const FrameLog&) = delete;
    FrameLog& operator=(const FrameLog&) = delete;
    void Write(const nlohmann::json& record) {
        const std::string line = record.dump() + "\n";
        if (std::fwrite(line.data(), 1, line.size(), file_) != line.size() || std::fflush(file_) != 0)
            Fail("failed writing '{}': {}", path_.string(), std::strerror(errno));
    }
    void Close() {
        std::FILE* file = std::exchange(file_, nullptr);
        if (file && std::fclose(file) != 0) Fail("failed writing '{}': {}", path_.string(), std::strerror(errno));
    }

private:
    std::filesystem::path path_;
    std::FILE* file_;
};

struct RunOptions {
    ConfigOptions config;
    std::string replay;      // --replay FILE
    bool allowChanges = false;
    std::string record;      // --record FILE
    bool score = false;      // --score: run.score = true
};

// The run's files, as the loop hands it each step: frames.jsonl (one line per frame, written as
// the frame completes), the inputs' EXRs and noisy PNGs, each variant's outputs and debug views,
// the counters and timing aggregates of the manifest; with run.score the scorer's calls, timed.
class RunFiles : public FrameLoopObserver {
public:
    RunFiles(const RunConfig& config, const std::filesystem::path& outDir, FrameLoop& loop, RunScorer* scorer,
             int frames)
        : config_(config), outDir_(outDir), loop_(loop), scorer_(scorer), frameLog_(outDir / "frames.jsonl"),
          progress_("rendering", frames) {}

    void Frame(const StereoFrame& frame) override {
        record_ = nlohmann::json();
        record_["frame"] = frame.frame;
        record_["time_s"] = frame.timeSeconds;
        record_["gaze_head"] = {frame.gaze.direction.x, frame.gaze.direction.y, frame.gaze.direction.z};
        if (loop_.Pipeline().GazeHeld(frame.frame)) record_["gaze_held"] = true;
        if (!frame.gaze.valid) {
            record_["blink"] = config_.gaze.blink;
            ++blinkFrames;
        }
        if (tracked_) {
            record_["true_gaze_head"] = {frame.trueGaze.direction.x, frame.trueGaze.direction.y,
                                         frame.trueGaze.direction.z};
            if (!frame.trueGaze.valid) record_["true_blink"] = true;
        }
    }

    void Eye(const StereoFrame& frame, int eye) override {
        const EyeFrame& e = frame.eyes[size_t(eye)];
        eyeRecord_ = nlohmann::json();
        eyeRecord_["gaze_pixel"] = {e.gazePixel.x, e.gazePixel.y};
        if (tracked_) eyeRecord_["true_gaze_pixel"] = {e.trueGazePixel.x, e.trueGazePixel.y};
        eyeRecord_["spp_ms"] = e.sppMs;
        eyeRecord_["render_ms"] = e.renderMs;
        timings.Add({"spp"}, e.sppMs);
        timings.Add({"render"}, e.renderMs);
        uint64_t samples = 0;
        for (size_t p = 0; p < e.sppMap.size(); ++p) samples += e.sppMap[p];
        totalSamples += samples;
        for (size_t p = 0; p < e.inputs.sampleCount.size(); ++p) recordedSamples += e.inputs.sampleCount[p];
        eyeRecord_["samples"] = samples;

        const auto writeStart = std::chrono::steady_clock::now();
        stem_ = FrameOutputStem(frame.frame, eye);
        if (config_.output.writeInputs)
            WriteFrameInputsExr(outDir_ / "inputs" / (stem_ + ".exr"), e.inputs, e.sppMap,
                                PlaneLayers(loop_.Pipeline().GetRenderer().Visibility(eye)));
        if (config_.output.writePng)
            WritePng(outDir_ / "noisy" / (stem_ + ".png"), e.inputs.NoisyImage(), config_.output.exposure);
        eyeRecord_["write_inputs_ms"] = MsSince(writeStart);
        timings.Add({"write_inputs"}, eyeRecord_["write_inputs_ms"].get<double>());
        denoiseRecord_ = nlohmann::json::object();
        record_[kEyeNames[eye]] = eyeRecord_;
    }

    void Reference(const StereoFrame& frame, int eye, const ReferenceLookup& reference) override {
        const auto scoreStart = std::chrono::steady_clock::now();
        scorer_->Reference(frame, eye, reference);
        timings.Add({"score_reference"}, reference.ms + MsSince(scoreStart));
    }

    void Output(const StereoFrame& frame, int eye, const DenoisedOutput& output) override {
        const std::string& name = *output.name;
        nlohmann::json passes = nlohmann::json::object();
        for (const PassTiming& t : output.denoiser->LastTimings()) {
            passes[t.pass] = t.ms;
            timings.Add({"denoise", name, "passes", t.pass}, t.ms);
        }
        timings.Add({"denoise", name, "wall"}, output.wallMs);
        denoiseRecord_[name] = {{"wall_ms", output.wallMs}, {"passes_ms", passes}};
        record_[kEyeNames[eye]]["denoise"] = denoiseRecord_;
        if (scorer_) {
            const auto scoreStart = std::chrono::steady_clock::now();
            scorer_->Output(frame, eye, output);
            timings.Add({"score_metrics"}, MsSince(scoreStart));
        }
        const std::filesystem::path dir = outDir_ / "denoised" / name;
        if (config_.output.writePng) WritePng(dir / (stem_ + ".png"), *output.image, config_.output.exposure);
        if (config_.output.writeExr) WriteRgbExr(dir / (stem_ + ".exr"), *output.image);
        if (config_.output.writeDebugViews) WriteDebugViewsExr(dir / (stem_ + ".debug.exr"), *output.denoiser);
    }

    void EndFrame(const StereoFrame& frame) override {
        for (int eye = 0; eye < 2; ++eye)
            if (!record_[kEyeNames[eye]].contains("denoise")) record_[kEyeNames[eye]]["denoise"] = nlohmann::json::object();
        frameLog_.Write(record_);
        if (framesRendered++ == 0) firstIndex = frame.frame;
        lastIndex = frame.frame;
        progress_.Step(fmt::format("frame {}", frame.frame));
    }

    void SetTracked(bool tracked) { tracked_ = tracked; }
    void Close() {
        progress_.Finish();
        frameLog_.Close();
    }

    TimingStats timings;
    uint64_t totalSamples = 0;
    uint64_t recordedSamples = 0;  // Σ FrameInputs::sampleCount: A-SVGF gradient pixels trace n_prev
    int framesRendered = 0;
    int blinkFrames = 0;  // frames whose gaze sample was invalid (gaze.blink says how rendered)
    uint32_t firstIndex = 0, lastIndex = 0;

private:
    const RunConfig& config_;
    std::filesystem::path outDir_;
    FrameLoop& loop_;
    RunScorer* scorer_;
    FrameLog frameLog_;
    Progress progress_;
    bool tracked_ = false;  // a modelled tracker: the frame's true gaze is recorded beside it
    nlohmann::json record_, eyeRecord_, denoiseRecord_;
    std::string stem_;
};

// `config` is the job's config; `replay` (optional) the recording it re-renders.
void RunFrames(const RunConfig& config, Replay* replay, const std::string& recordPath) {
    namespace fs = std::filesystem;
    EnforceRunBudget(config, "run");
    OutputDir out(config.output.dir, "output.dir");
    out.Lock();
    // An earlier run's outputs (a stale manifest, frames beyond this run's) never sit beside this one's.
    out.MoveAsideEarlierOutputs(false);
    const fs::path outDir = out.Path();

    auto totalStart = std::chrono::steady_clock::now();
    if (config.run.score && config.denoise.denoisers.empty())
        Fail("run.score: denoise.denoisers is empty (nothing to score)");
    const RunConfig pipelineConfig = replay ? ReplayPipelineConfig(config) : config;
    FrameLoop loop(config, config.run.score, &pipelineConfig);
    FramePipeline& pipeline = loop.Pipeline();
    if (replay) CheckReplayScene(*replay, pipeline);
    FrameSequence sequence = replay ? FrameSequence(pipeline, *replay) : FrameSequence(pipeline);
    DenoiserSet& denoisers = loop.Denoisers();
    std::optional<OutputDir> cacheDir;  // before any rendering, as the experiment's
    std::optional<RunScorer> scorer;
    if (config.run.score) {
        cacheDir.emplace(config.reference.cacheDir, "reference.cache_dir");
        scorer.emplace(config, loop);
    }
    std::optional<SessionRecorder> recorder;
    if (!recordPath.empty() && config.run.warmupFrames > 0)
        Fail("--record: run.warmup_frames = {}: a recording replays from its first frame, so it cannot hold frames "
             "that were not scored (set it to 0)", config.run.warmupFrames);
    if (!recordPath.empty()) recorder.emplace(recordPath, ConfigToJson(config), SessionHeaderExtra(pipeline));
    std::fprintf(stderr, "fovrt run: scene '%s', %d frames%s, %d×%d per eye, denoisers on %s -> %s\n",
                 pipeline.GetScene().name.c_str(), sequence.Scored(),
                 replay ? (" replayed from " + replay->file.string()).c_str() : "", config.camera.width,
                 config.camera.height, denoisers.DeviceDescription().c_str(), outDir.string().c_str());

    RunFiles files(config, outDir, loop, scorer ? &*scorer : nullptr, sequence.Scored());
    loop.Attach(files);
    RecordedFrame recorded;
    auto next = [&](FrameRequest& request) {
        if (!sequence.Next(recorded)) return false;
        if (recorder) recorder->Append(recorded);
        files.SetTracked(recorded.request.trueGaze.has_value());
        request = recorded.request;
        return true;
    };
    try {
        loop.RunSeed(0, SeedWork{config.run.seed, {}}, next);
        ThrowIfInterrupted();
        files.Close();
        if (recorder) recorder->Close();

        RenderStats stats = pipeline.GetRenderer().Stats();
        nlohmann::json manifest;
        manifest["command"] = "run";
        manifest["complete"] = true;
        manifest["build"] = BuildInfoJson();
        manifest["config"] = ConfigToJson(config);
        manifest["seed"] = config.run.seed;
        manifest["scene"] = {{"name", pipeline.GetScene().name},
                             {"source", pipeline.GetScene().sourcePath.string()},
                             {"frame_rate", pipeline.FramesPerSecond()}};
        if (replay) manifest["replay"] = replay->ToJson();
        if (recorder) manifest["recorded_to"] = recorder->Path().string();
        manifest["denoise_device"] = denoisers.DeviceDescription();
        // What denoise.precision (auto by default) resolved to on that device.
        manifest["denoise_storage"] = denoisers.StorageDescription();
        // Derived from the foveation, not a config key (RunDenoiseConfig).
        manifest["denoise_sample_counts_may_be_zero"] = RunDenoiseConfig(config).params.sampleCountsMayBeZero;
        manifest["counters"] = {{"samples", files.totalSamples},
                                {"recorded_samples", files.recordedSamples},
                                {"traced_samples", stats.samples},
                                {"rays", stats.Rays()},
                                {"primary_rays", stats.primaryRays},
                                {"guide_rays", stats.guideRays},
                                {"shadow_tests", stats.shadowRays},
                                {"shadow_rays_reused", stats.shadowRaysReused},
                                {"bounce_rays", stats.bounceRays},
                                {"dropped_nonfinite_samples", stats.droppedSamples},
                                {"blink_frames", files.blinkFrames}};
        nlohmann::json replaced = nlohmann::json::object();
        for (size_t v = 0; v < denoisers.size(); ++v) {
            uint64_t nonFinite = 0, negative = 0;
            for (int eye = 0; eye < 2; ++eye) {
                nonFinite += denoisers.At(v, eye).Stats().nonFiniteSamples;
                negative += denoisers.At(v, eye).Stats().negativeSamples;
            }
            replaced[denoisers.Name(v)] = {{"nonfinite", nonFinite}, {"negative", negative}};
        }
        manifest["counters"]["denoiser_replaced_samples"] = replaced;
        // Per-frame records are frames.jsonl's lines; the manifest keeps their count and the timings'
        // aggregates (per eye and frame), so it stays the same size however long the run.
        manifest["frames"] = {{"count", files.framesRendered},
                              {"first", files.firstIndex},
                              {"last", files.lastIndex},
                              {"records", "frames.jsonl"}};
        if (scorer) manifest["score"] = scorer->Finish(outDir, denoisers.Name(0));
        manifest["timings_ms"] = files.timings.ToJson();
        manifest["total_s"] = MsSince(totalStart) / 1000.0;
        WriteTextAtomically(outDir / "manifest.json", manifest.dump(2) + "\n");
        out.Keep();
        if (cacheDir) cacheDir->Keep();
        std::fprintf(stderr, "fovrt run: %d frames in %.1f s, %.2f Mrays, manifest %s\n",
                     files.framesRendered, MsSince(totalStart) / 1000.0, double(stats.Rays()) * 1e-6,
                     (outDir / "manifest.json").string().c_str());
    } catch (const Interrupted& e) {
        out.Keep();  // the frames written so far stay, and the message says so
        if (cacheDir) cacheDir->Keep();  // every cache entry is complete (written atomically)
        throw Interrupted(e.Signal(), fmt::format("{}: {} of {} frames written in {}; no manifest", e.what(),
                                                  files.framesRendered, sequence.Scored(), outDir.string()));
    }
}

// RunFrames with an allocation failure as one line naming the resolution and the planned bytes.
void Run(const RunConfig& config, Replay* replay, const std::string& recordPath) {
    try {
        RunFrames(config, replay, recordPath);
    } catch (const std::bad_alloc&) {
        FailOutOfMemory(config, PlanRunMemory(config), "fovrt run");
    }
}

void RunCommand(const RunOptions& options) {
    InterruptScope interrupts;
    if (options.allowChanges && options.replay.empty()) Fail("--allow-changes needs --replay FILE");
    auto withScore = [&](RunConfig config) {
        if (options.score) config.run.score = true;
        return config;
    };
    if (options.replay.empty()) {
        Run(withScore(ResolveConfig(options.config)), nullptr, options.record);
        return;
    }
    if (!options.record.empty() && std::filesystem::exists(options.record) &&
        std::filesystem::equivalent(options.record, options.replay))
        Fail("--record {}: is the recording being replayed", options.record);
    Replay replay = OpenReplay(options.replay, options.allowChanges);
    RunConfig config = ResolveReplayConfig(replay, options.config, ResolveConfig, "fovrt run");
    Run(withScore(config), &replay, options.record);
}

}  // namespace

void RegisterRunCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "run", "Headless job: render N stereo frames with foveated spp maps, write FrameInputs EXRs, "
               "denoise, write a run manifest");
    auto options = std::make_shared<RunOptions>();
    AddConfigOptions(cmd, options->config);
    AddReplayOptions(cmd, options->replay, options->allowChanges);
    cmd->add_option("--record", options->record, "Record the rendered frames as a session recording (JSON Lines)");
    cmd->add_flag("--score", options->score,
                  "Score every variant against the cached references as `experiment` does (run.score = true): "
                  "frames-<scene>.csv, jod.csv, summary.json and the manifest's \"score\"");
    cmd->callback([options] { RunCommand(*options); });
}

}  // namespace fovrt
