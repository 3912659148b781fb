// The two halves of `fovrt experiment`, for the whole experiment, its shards and each point of a
// sampling-design sweep (app/design_sweep.h): computing runs, and writing the outputs of the runs
// computed (by one machine or merged from its shards).
#pragma once

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "app/experiment.h"
#include "app/experiment_shards.h"

namespace fovrt {

// Computes the runs in `units` (all of them for a single machine): per scene, one frame loop (the
// scene and its BVH built once, the references from the shared cache); per run seed that has a
// run, the frames are rendered once (stereo) and fed to the runs' denoisers. What is kept of them
// comes from the observers of app/experiment_pass.h. EXR outputs go under `outDir`.
ExperimentPart ComputeRuns(const ExperimentSpec& spec, const std::vector<RunUnit>& units,
                           const std::filesystem::path& outDir);

enum class ExperimentOutputs {
    kPrinted,    // the files, the tables on stdout and the timings on stderr
    kFilesOnly,  // the files (a sweep's point: the sweep prints its own table)
};

// The outputs of a whole experiment (frames CSVs, summary.json, jod.csv, gaze CSVs, report,
// manifest), from one machine's part or the merged parts of its shards. Moves the report's images
// out of `part`.
Results WriteExperimentOutputs(const ExperimentSpec& spec, ExperimentPart& part, const std::filesystem::path& outDir,
                               std::chrono::steady_clock::time_point totalStart,
                               ExperimentOutputs outputs = ExperimentOutputs::kPrinted);

// What a missing shard's message tells the user to run.
std::string RerunCommand(const ExperimentSpec& spec);

}  // namespace fovrt
