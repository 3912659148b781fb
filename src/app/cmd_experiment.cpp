// `fovrt experiment FILE [--quick] [--replay REC]`: same noisy inputs, several denoisers, metrics per region
// against a cached reference; CSV, summary JSON, stdout table and an HTML report (experiment.h).
#include "app/commands.h"
#include "app/config_cli.h"
#include "app/experiment.h"

namespace fovrt {

void RegisterExperimentCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "experiment", "Compare denoisers on identical foveated inputs against a high-spp reference");
    auto options = std::make_shared<ConfigOptions>();
    auto quick = std::make_shared<bool>(false);
    auto scenes = std::make_shared<std::vector<std::string>>();
    cmd->add_option("file", options->configPath, "Experiment file (presets/*.toml)")->required();
    cmd->add_flag("--quick", *quick, "Apply the file's [experiment.quick] overrides (a smoke run)");
    cmd->add_option("--scene", *scenes, "Run only these scenes (repeatable; replaces experiment.scenes)");
    cmd->add_option("--set", options->sets, "Override a config key: section.key=value (TOML value)");
    cmd->add_option("--memory-budget", options->memoryBudget, "Refuse to start above BYTES (e.g. 2GiB)");
    auto replay = std::make_shared<std::string>();
    auto allowChanges = std::make_shared<bool>(false);
    cmd->add_option("--replay", *replay,
                    "Render a session recording's frames (its scene, cameras and gaze) instead of the scene's path");
    cmd->add_flag("--allow-changes", *allowChanges,
                  "With --replay: accept config changes that make the frames differ from the recording");
    cmd->callback([options, quick, scenes, replay, allowChanges] {
        RunExperiment(LoadExperiment(*options, *quick, *scenes, *replay, *allowChanges));
    });
}

}  // namespace fovrt
