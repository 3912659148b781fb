// `fovrt config`: prints the fully resolved configuration (defaults <- -c FILE <- --set <-
// --memory-budget) as TOML, or as JSON with --json, after the same validation every command runs.
// --keys lists the denoiser parameters from their tables (denoise/params.cpp).
#include <cstdio>
#include <memory>
#include <string>
#include <type_traits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "config/config_cli.h"
#include "config/config_io.h"
#include "commands.h"

namespace fovrt {
namespace {

// One line per [denoise.*] key: key, default, range, doc.
void PrintDenoiserKeys() {
    constexpr const char* kLine = "{:<44} {:<8} {:<14} {}\n";
    fmt::print(kLine, "key", "default", "range", "doc");
    std::string names;
    for (const PrecisionRow& row : PrecisionTable()) names += (names.empty() ? "" : "|") + std::string(row.name);
    const DenoiserParams defaults;
    fmt::print(kLine, kPrecisionKey, PrecisionName(defaults.precision), names, kPrecisionDoc);
    ForEachDenoiserParam(defaults, [&](const ParamInfo& info, const auto& value) {
        const bool isBool = std::is_same_v<std::decay_t<decltype(value)>, bool>;
        fmt::print(kLine, info.key, value, isBool ? "true|false" : info.range.Describe(), info.doc);
    });
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
    cmd->add_flag("--keys", *keys, "List the [denoise.*] keys: default, range and meaning");
    cmd->callback([options, json, experiment, quick, keys] {
        if (*keys) {
            PrintDenoiserKeys();
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
