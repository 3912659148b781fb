// `fovrt experiment`: the research workflow. For each scene and each run seed, renders every
// frame once per eye (noisy FrameInputs + the cached high-spp reference, which has its own fixed
// seed and so is shared by every run seed), feeds identical inputs to every listed denoiser
// variant, and scores each output per region (whole, fovea, periphery, eccentricity bands)
// against the reference. Writes a per-frame CSV per scene (every value, with its seed), a
// summary JSON with robust summaries and bootstrap intervals (app/experiment_stats.h), the table
// on stdout, a self-contained HTML report and a manifest that records everything needed to
// rerun. Same config and seeds -> identical CSV. With a session recording (--replay), the frames
// are the recording's (cameras, gaze, scene time) instead of the scene's camera path.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "config/config.h"
#include "app/replay.h"
#include "app/experiment_shards.h"
#include "app/report.h"
#include "app/sampling_designs.h"
#include "metrics/regions.h"

namespace fovrt {

struct ConfigOptions;  // config/config_cli.h

// A scene's label in file names, reports and manifests: its `name` (not the path it was given
// by), reduced to [A-Za-z0-9._-] so it is one path component under output.dir; a label already
// in `used` gets "-2", "-3", ... (the label returned is appended to `used`).
std::string SceneLabel(const std::string& name, std::vector<std::string>& used);

// The frames a run scores, as its report states them: "8", or "8 from frame 8, after 8 warm-up
// frames" (run.warmup_frames).
std::string ScoredFramesText(const RunSettings& run);

// An experiment file: a RunConfig plus an [experiment] table (scenes, variants, quick overrides).
struct ExperimentSpec {
    std::filesystem::path file;
    RunConfig config;                   // resolved (quick overrides and --set applied)
    std::vector<std::string> scenes;    // each replaces scene.name
    std::vector<std::string> variants;  // becomes denoise.denoisers
    std::string baseline;               // experiment.baseline, else the first variant
    std::vector<uint32_t> seeds;        // run seeds, each a full pass (--seeds / experiment.seeds; else run.seed)
    int visualFrame = -1;               // frame shown in the report's images; -1 = the last
    bool suppressSaccades = false;      // experiment.suppress_saccades: statistics without saccade frames
    bool quick = false;
    ShardSelection shard;               // --shard I/N: compute one block of the runs (experiment_shards.h)
    bool merge = false;                 // --merge: combine the shards' parts into the outputs
    // --replay: every frame comes from this recording, whose scene is the only one; the config is
    // the recording's with the file and --set on top (app/replay.h says which keys may differ).
    std::optional<Replay> replay;
    // experiment.designs / budgets: every point runs the whole experiment above with its own
    // sampling (app/sampling_designs.h); inactive when the file names no designs.
    SamplingSweep sweep;
    // The foveation whose fovea the errors and the measured sampling are taken in (MetricFovea);
    // none: config.foveation's. A sweep's points take the experiment's own, so every design is
    // scored in the same fovea.
    std::optional<FoveationParams> scoredFoveation;
};

// The command line of `fovrt experiment` beyond the config options.
struct ExperimentArgs {
    bool quick = false;
    std::vector<std::string> scenes;  // non-empty: replaces experiment.scenes (`--scene veach-ajar`)
    std::string replayPath;           // non-empty: the recording to replay
    bool allowChanges = false;        // --allow-changes (with --replay)
    std::string seeds;                // --seeds: "N" (run.seed, run.seed+1, ...) or "1,5,9"; "" = file
    std::string shard;                // --shard I/N
    bool merge = false;               // --merge
};

// The seeds of `--seeds TEXT`: a count N ≥ 1 (first, first+1, ..., first+N−1) or a
// comma-separated list of distinct integers in [0, 2^32). Bad text: one error naming --seeds.
std::vector<uint32_t> ParseSeedsOption(const std::string& text, uint32_t first);

ExperimentSpec LoadExperiment(const ConfigOptions& options, const ExperimentArgs& args = {});

// Runs the experiment and writes its outputs under spec.config.output.dir. Returns the results.
Results RunExperiment(const ExperimentSpec& spec);

}  // namespace fovrt
