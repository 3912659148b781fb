// `fovrt experiment`: the research workflow. For each scene, renders every frame once per eye
// (noisy FrameInputs + the cached high-spp reference), feeds identical inputs to every listed
// denoiser variant, and scores each output per region (whole, fovea, periphery, eccentricity
// bands) against the reference. Writes a per-frame CSV per scene, a summary JSON, the thesis-style
// table on stdout, a self-contained HTML report and a manifest that records everything needed to
// rerun. Same config and seed -> identical CSV. With a session recording (--replay), the frames
// are the recording's (cameras, gaze, scene time) instead of the scene's camera path.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/config.h"
#include "app/replay.h"
#include "app/report.h"
#include "metrics/regions.h"

namespace fovrt {

struct ConfigOptions;  // app/config_cli.h

// The fovea the metrics use (and the live preview outlines): the disc model's spp disc, the
// linear model's full-rate angle, else the first eccentricity band (5°).
FoveaRadius MetricFovea(const FoveationParams& foveation, int imageWidth);

// An experiment file: a RunConfig plus an [experiment] table (scenes, variants, quick overrides).
struct ExperimentSpec {
    std::filesystem::path file;
    RunConfig config;                   // resolved (quick overrides and --set applied)
    std::vector<std::string> scenes;    // each replaces scene.name
    std::vector<std::string> variants;  // becomes denoise.denoisers; "svgf" is the baseline
    int visualFrame = -1;               // frame shown in the report's images; -1 = the last
    bool quick = false;
    // --replay: every frame comes from this recording, whose scene is the only one; the config is
    // the recording's with the file and --set on top (app/replay.h says which keys may differ).
    std::optional<Replay> replay;
};

// `scenes`: when non-empty, replaces the file's experiment.scenes (e.g. `--scene veach-ajar`).
// `replayPath`: when non-empty, the recording to replay (`allowChanges`: its --allow-changes).
ExperimentSpec LoadExperiment(const ConfigOptions& options, bool quick,
                              const std::vector<std::string>& scenes = {},
                              const std::string& replayPath = "", bool allowChanges = false);

// Runs the experiment and writes its outputs under spec.config.output.dir. Returns the results.
Results RunExperiment(const ExperimentSpec& spec);

}  // namespace fovrt
