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
#include "core/error.h"
#include "core/interrupt.h"
#include "denoise/memory_plan.h"
#include "io/exr.h"
#include "io/png.h"
#include "pipeline/build_info.h"
#include "pipeline/denoiser_set.h"
#include "pipeline/frame_pipeline.h"
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

double MsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
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
    FramePipeline pipeline(replay ? ReplayPipelineConfig(config) : config);
    if (replay) CheckReplayScene(*replay, pipeline);
    FrameSequence sequence = replay ? FrameSequence(pipeline, *replay) : FrameSequence(pipeline);
    DenoiserSet denoisers(config.denoise);
    std::optional<OutputDir> cacheDir;  // before any rendering, as the experiment's
    std::optional<RunScorer> scorer;
    if (config.run.score) {
        if (config.denoise.denoisers.empty()) Fail("run.score: denoise.denoisers is empty (nothing to score)");
        cacheDir.emplace(config.reference.cacheDir, "reference.cache_dir");
        scorer.emplace(config, pipeline);
    }
    std::optional<SessionRecorder> recorder;
    if (!recordPath.empty()) recorder.emplace(recordPath, ConfigToJson(config), SessionHeaderExtra(pipeline));
    std::fprintf(stderr, "fovrt run: scene '%s', %d frames%s, %d×%d per eye, denoisers on %s -> %s\n",
                 pipeline.GetScene().name.c_str(), sequence.Count(),
                 replay ? (" replayed from " + replay->file.string()).c_str() : "", config.camera.width,
                 config.camera.height, denoisers.DeviceDescription().c_str(), outDir.string().c_str());

    FrameLog frameLog(outDir / "frames.jsonl");
    TimingStats timings;
    Progress progress("rendering", sequence.Count());
    RecordedFrame request;
    StereoFrame frame;
    Plane<vec3> denoised;
    uint64_t totalSamples = 0;
    uint64_t recordedSamples = 0;  // Σ FrameInputs::sampleCount: A-SVGF gradient pixels trace n_prev
    int framesRendered = 0;
    int blinkFrames = 0;  // frames whose gaze sample was invalid (gaze.blink says how rendered)
    uint32_t firstIndex = 0, lastIndex = 0;
    try {
        while (sequence.Next(request)) {
            ThrowIfInterrupted();
            const uint32_t index = request.request.frame;
            pipeline.Render(request.request, frame);
            if (recorder) recorder->Append(request);

            nlohmann::json record;
            record["frame"] = index;
            record["time_s"] = frame.timeSeconds;
            record["gaze_head"] = {frame.gaze.direction.x, frame.gaze.direction.y,
                                   frame.gaze.direction.z};
            if (pipeline.GazeHeld(index)) record["gaze_held"] = true;
            if (!frame.gaze.valid) {
                record["blink"] = config.gaze.blink;
                ++blinkFrames;
            }
            const bool tracked = request.request.trueGaze.has_value();  // a modelled tracker: where the eye was
            if (tracked) {
                record["true_gaze_head"] = {frame.trueGaze.direction.x, frame.trueGaze.direction.y,
                                            frame.trueGaze.direction.z};
                if (!frame.trueGaze.valid) record["true_blink"] = true;
            }
            for (int eye = 0; eye < 2; ++eye) {
                EyeFrame& e = frame.eyes[size_t(eye)];
                nlohmann::json eyeRecord;
                eyeRecord["gaze_pixel"] = {e.gazePixel.x, e.gazePixel.y};
                if (tracked) eyeRecord["true_gaze_pixel"] = {e.trueGazePixel.x, e.trueGazePixel.y};
                eyeRecord["spp_ms"] = e.sppMs;
                eyeRecord["render_ms"] = e.renderMs;
                timings.Add({"spp"}, e.sppMs);
                timings.Add({"render"}, e.renderMs);
                uint64_t samples = 0;
                for (size_t p = 0; p < e.sppMap.size(); ++p) samples += e.sppMap[p];
                totalSamples += samples;
                for (size_t p = 0; p < e.inputs.sampleCount.size(); ++p) recordedSamples += e.inputs.sampleCount[p];
                eyeRecord["samples"] = samples;

                auto writeStart = std::chrono::steady_clock::now();
                std::string stem = FrameOutputStem(index, eye);
                if (config.output.writeInputs)
                    WriteFrameInputsExr(outDir / "inputs" / (stem + ".exr"), e.inputs, e.sppMap,
                                        PlaneLayers(pipeline.GetRenderer().Visibility(eye)));
                if (config.output.writePng) {
                    WritePng(outDir / "noisy" / (stem + ".png"), e.inputs.NoisyImage(),
                             config.output.exposure);
                }
                eyeRecord["write_inputs_ms"] = MsSince(writeStart);
                timings.Add({"write_inputs"}, eyeRecord["write_inputs_ms"].get<double>());

                if (scorer) {
                    const auto scoreStart = std::chrono::steady_clock::now();
                    scorer->BeginEye(frame, eye);
                    timings.Add({"score_reference"}, MsSince(scoreStart));
                }
                nlohmann::json denoiseRecord = nlohmann::json::object();
                for (size_t v = 0; v < denoisers.size(); ++v) {
                    Denoiser& denoiser = denoisers.At(v, eye);
                    auto start = std::chrono::steady_clock::now();
                    denoiser.Denoise(e.inputs, denoised);
                    const double wallMs = MsSince(start);
                    nlohmann::json passes = nlohmann::json::object();
                    for (const PassTiming& t : denoiser.LastTimings()) {
                        passes[t.pass] = t.ms;
                        timings.Add({"denoise", denoisers.Name(v), "passes", t.pass}, t.ms);
                    }
                    timings.Add({"denoise", denoisers.Name(v), "wall"}, wallMs);
                    denoiseRecord[denoisers.Name(v)] = {{"wall_ms", wallMs}, {"passes_ms", passes}};
                    if (scorer) {
                        const auto scoreStart = std::chrono::steady_clock::now();
                        scorer->AddOutput(denoisers.Name(v), denoised);
                        timings.Add({"score_metrics"}, MsSince(scoreStart));
                    }
                    fs::path dir = outDir / "denoised" / denoisers.Name(v);
                    if (config.output.writePng)
                        WritePng(dir / (stem + ".png"), denoised, config.output.exposure);
                    if (config.output.writeExr) WriteRgbExr(dir / (stem + ".exr"), denoised);
                    if (config.output.writeDebugViews) WriteDebugViewsExr(dir / (stem + ".debug.exr"), denoiser);
                }
                eyeRecord["denoise"] = denoiseRecord;
                record[kEyeNames[eye]] = eyeRecord;
            }
            frameLog.Write(record);
            if (framesRendered++ == 0) firstIndex = index;
            lastIndex = index;
            progress.Step(fmt::format("frame {}", index));
        }
        ThrowIfInterrupted();
        progress.Finish();
        frameLog.Close();
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
        manifest["counters"] = {{"samples", totalSamples},
                                {"recorded_samples", recordedSamples},
                                {"traced_samples", stats.samples},
                                {"rays", stats.Rays()},
                                {"primary_rays", stats.primaryRays},
                                {"shadow_tests", stats.shadowRays},
                                {"shadow_rays_reused", stats.shadowRaysReused},
                                {"bounce_rays", stats.bounceRays},
                                {"dropped_nonfinite_samples", stats.droppedSamples},
                                {"blink_frames", blinkFrames}};
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
        manifest["frames"] = {{"count", framesRendered},
                              {"first", firstIndex},
                              {"last", lastIndex},
                              {"records", "frames.jsonl"}};
        if (scorer) manifest["score"] = scorer->Finish(outDir, denoisers.Name(0));
        manifest["timings_ms"] = timings.ToJson();
        manifest["total_s"] = MsSince(totalStart) / 1000.0;
        WriteTextAtomically(outDir / "manifest.json", manifest.dump(2) + "\n");
        out.Keep();
        if (cacheDir) cacheDir->Keep();
        std::fprintf(stderr, "fovrt run: %d frames in %.1f s, %.2f Mrays, manifest %s\n",
                     framesRendered, MsSince(totalStart) / 1000.0, double(stats.Rays()) * 1e-6,
                     (outDir / "manifest.json").string().c_str());
    } catch (const Interrupted& e) {
        out.Keep();  // the frames written so far stay, and the message says so
        if (cacheDir) cacheDir->Keep();  // every cache entry is complete (written atomically)
        throw Interrupted(e.Signal(), fmt::format("{}: {} of {} frames written in {}; no manifest", e.what(),
                                                  framesRendered, sequence.Count(), outDir.string()));
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
