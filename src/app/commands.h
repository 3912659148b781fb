// Subcommands of the `fovrt` executable. Each lives in its own cmd_<name>.cpp and registers its
// options and callback on the CLI11 app.
#pragma once

#include <CLI/CLI.hpp>

namespace fovrt {

void RegisterInfoCommand(CLI::App& app);
void RegisterConfigCommand(CLI::App& app);
void RegisterRunCommand(CLI::App& app);
void RegisterExperimentCommand(CLI::App& app);
void RegisterReferenceCommand(CLI::App& app);
void RegisterDatasetCommand(CLI::App& app);  // RAE training data (training/)
void RegisterBenchCommand(CLI::App& app);
void RegisterMemoryCommand(CLI::App& app);
void RegisterPreviewCommand(CLI::App& app);  // runs src/preview
void RegisterXrCommand(CLI::App& app);       // runs src/xr
void RegisterClusterCommand(CLI::App& app);
void RegisterVdpCommand(CLI::App& app);  // FovVideoVDP between two frame sequences
void RegisterRaysSavedCommand(CLI::App& app);  // rays saved from sweeps that ran apart

}  // namespace fovrt
