// `fovrt config`: prints the fully resolved configuration (defaults <- -c FILE <- --set <-
// --memory-budget) as TOML, or as JSON with --json, after the same validation every command runs.
// --keys lists every key from the settings tables (config/settings_tables.h).
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "config/config_cli.h"
#include "config/config_io.h"
#include "config/settings_tables.h"
#include "commands.h"

namespace fovrt {
namespace {

// One line per key: key, default, allowed values, meaning (config/settings_tables.h).
void PrintKeys() {
    constexpr const char* kLine = "{:<40} {:<14} {:<24} {}\n";
    fmt::print(kLine, "key", "default", "allowed", "meaning");
    for (const SettingLine& line : DescribeSettings())
        fmt::print(kLine, line.key, line.defaultValue.empty() ? "(absent)" : line.defaultValue, line.allowed, line.doc);
}

}  // namespace

void RegisterConfigCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("config", "Print the resolved configuration (TOML, or JSON with --json)");
    auto options = std::make_shared<ConfigOptions>();
    auto json = std::make_shared<bool>(false);
    auto experiment = std::make_shared<bool>(false);
    auto quick = std::make_shared<bool>(false);
    auto keys = std::make_shared<bool>(false);
    AddConfigOptions(cmd, *options);
    cmd->add_flag("--json", *json, "Print JSON (as in run manifests) instead of TOML");
    cmd->add_flag("--experiment", *experiment, "The file is an experiment file: skip its [experiment] table");
    cmd->add_flag("--quick", *quick, "With --experiment: merge [experiment.quick] over the file");
    cmd->add_flag("--keys", *keys, "List every config key: default, allowed values and meaning");
    cmd->callback([options, json, experiment, quick, keys] {
        if (*keys) {
            PrintKeys();
            return;
        }
        ExperimentTable experimentTable;
        RunConfig config = *experiment || *quick
                               ? ResolveExperimentConfig(*options, *quick, experimentTable)
                               : ResolveConfig(*options);
        std::string text = *json ? ConfigToJson(config).dump(2) + "\n" : ConfigToToml(config);
        std::fputs(text.c_str(), stdout);
    });
}

}  // namespace fovrt
