// `fovrt experiment FILE [--quick] [--seeds N|LIST] [--replay REC]`: same noisy inputs, several denoisers,
// metrics per region against a cached reference, over several run seeds; CSV, summary JSON with
// bootstrap intervals, stdout table and an HTML report (experiment.h).
#include "app/commands.h"
#include "config/config_cli.h"
#include "app/experiment.h"
#include "app/shared_options.h"
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
    AddConfigOverrideOptions(cmd, *options);
    AddReplayOptions(cmd, args->replayPath, args->allowChanges);
    cmd->add_option("--shard", args->shard,
                    "Compute shard I of N (I/N, 0-based) of the (scene, seed, eye, variant) runs into "
                    "<output.dir>/shards; --merge combines them");
    cmd->add_flag("--merge", args->merge,
                  "Combine <output.dir>/shards into the CSV, summary, table and report a single run writes");
    cmd->callback([options, args] {
        InterruptScope interrupts;
        RunExperiment(LoadExperiment(*options, *args));
    });
}

}  // namespace fovrt
