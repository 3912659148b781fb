// Command-line plumbing shared by every subcommand: -c FILE, --set key=value, --memory-budget,
// resolved into a RunConfig (sources and their order: config/config.h).
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "config/config.h"

namespace CLI {
class App;
}

namespace fovrt {

struct ConfigOptions {
    std::string configPath;            // -c/--config FILE
    std::vector<std::string> sets;     // --set section.key=value (repeatable, in order)
    std::string memoryBudget;          // --memory-budget BYTES (empty = not given)
    // For commands whose files carry their own tables (e.g. [experiment]): top-level tables the
    // schema skips (no unknown-key error), and dotted tables of the file merged over its root
    // before the --set overrides, in order (e.g. "experiment.quick" for --quick). Not CLI options:
    // the command sets them.
    std::vector<std::string> ignoredTables;
    std::vector<std::string> overlayTables;
    // A resolved config (e.g. a session recording's, as ConfigToJson writes it) that replaces the
    // built-in defaults under -c and --set; null = the defaults. `baseOrigin` names it in errors.
    nlohmann::json base;
    std::string baseOrigin;
};
// -c/--config, then AddConfigOverrideOptions.
void AddConfigOptions(CLI::App* command, ConfigOptions& options);
// --set and --memory-budget: for commands whose config file is a positional argument.
void AddConfigOverrideOptions(CLI::App* command, ConfigOptions& options);
RunConfig ResolveConfig(const ConfigOptions& options);

// An experiment file's [experiment] table after every --set experiment.KEY, and where each of its
// keys came from ("exp.toml:4", "--set experiment.seeds=[1,2]").
struct ExperimentTable {
    toml::table table;
    std::map<std::string, std::string> origins;  // key below experiment. → origin
    std::string file;                            // the experiment file (origin of absent keys)
    std::string Origin(const std::string& key) const;
};

// Experiment files (presets/*.toml): a RunConfig plus an [experiment] table. Resolves the config
// with [experiment] skipped by the schema and, when `quick`, [experiment.quick] merged over the
// file (before --set); returns the [experiment] table (the file's with the --set experiment.KEY
// overrides; empty if neither has one) in `experiment`.
RunConfig ResolveExperimentConfig(const ConfigOptions& options, bool quick, ExperimentTable& experiment);

}  // namespace fovrt
