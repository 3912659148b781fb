// `fovrt experiment FILE [--quick] [--seeds N|LIST] [--replay REC]`: same noisy inputs, several denoisers,
// metrics per region against a cached reference, over several run seeds; CSV, summary JSON with
// bootstrap intervals, stdout table and an HTML report (experiment.h).
#include "app/commands.h"
#include "config/config_cli.h"
#include "app/experiment.h"
#include "core/interrupt.h"

namespace fovrt {

void RegisterExperimentCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "experiment", "Compare denoisers on identical foveated inputs against a high-spp reference");
    auto options = std::make_shared<ConfigOptions>();
    auto args = std::make_shared<ExperimentArgs>();
    cmd->add_option("file", options->configPath, "Experiment file (presets/*.toml)")->required();
    cmd->add_flag("--quick", args->quick, "Apply the file's [experiment.quick] overrides (a smoke run)");
    cmd->add_option("--scene", args->scenes, "Run only these scenes (repeatable; replaces experiment.scenes)");
    cmd->add_option("--seeds", args->seeds,
                    "Run seeds: N (run.seed ... run.seed+N-1) or a list 1,2,3 (replaces experiment.seeds)");
    cmd->add_option("--set", options->sets, "Override a config key: section.key=value (TOML value)");
    cmd->add_option("--memory-budget", options->memoryBudget, "Refuse to start above BYTES (e.g. 2GiB)");
    cmd->add_option("--replay", args->replayPath,
                    "Render a session recording's frames (its scene, cameras and gaze) instead of the scene's path");
    cmd->add_option("--shard", args->shard,
                    "Compute shard I of N (I/N, 0-based) of the (scene, seed, eye, variant) runs into "
                    "<output.dir>/shards; --merge combines them");
    cmd->add_flag("--merge", args->merge,
                  "Combine <output.dir>/shards into the CSV, summary, table and report a single run writes");
    cmd->add_flag("--allow-changes", args->allowChanges,
                  "With --replay: accept config changes that make the frames differ from the recording");
    cmd->callback([options, args] {
        InterruptScope interrupts;
        RunExperiment(LoadExperiment(*options, *args));
    });
}

}  // namespace fovrt
