// `fovrt config`: prints the fully resolved configuration (defaults <- -c FILE <- --set <-
// --memory-budget) as TOML, or as JSON with --json, after the same validation every command runs.
#include <cstdio>
#include <memory>

#include <nlohmann/json.hpp>

#include "app/config_cli.h"
#include "app/config_io.h"
#include "commands.h"

namespace fovrt {

void RegisterConfigCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("config", "Print the resolved configuration (TOML, or JSON with --json)");
    auto options = std::make_shared<ConfigOptions>();
    auto json = std::make_shared<bool>(false);
    auto experiment = std::make_shared<bool>(false);
    auto quick = std::make_shared<bool>(false);
    AddConfigOptions(cmd, *options);
    cmd->add_flag("--json", *json, "Print JSON (as in run manifests) instead of TOML");
    cmd->add_flag("--experiment", *experiment, "The file is an experiment file: skip its [experiment] table");
    cmd->add_flag("--quick", *quick, "With --experiment: merge [experiment.quick] over the file");
    cmd->callback([options, json, experiment, quick] {
        toml::table experimentTable;
        RunConfig config = *experiment || *quick
                               ? ResolveExperimentConfig(*options, *quick, experimentTable)
                               : ResolveConfig(*options);
        std::string text = *json ? ConfigToJson(config).dump(2) + "\n" : ConfigToToml(config);
        std::fputs(text.c_str(), stdout);
    });
}

}  // namespace fovrt
