// The thesis protocol's frames (presets/thesis-foveated.toml with its [experiment.quick] overlay:
// foveated 8/1 spp disc, Lissajous gaze, α = 0.05, 2 à-trous iterations) at the scenes' 30 fps,
// denoised on the C++ reference: what app_two_history_stable_test and
// tests/tools/two_history_flicker_probe render. Header only: both link fovrt_app.
#pragma once

#include <string>
#include <vector>

#include "app/experiment.h"
#include "config/config_cli.h"

namespace fovrt::test {

// The preset's resolved config for `scene`, with `sets` (key=value) applied after the quick
// overlay (e.g. "camera.width=160").
inline RunConfig ThesisPresetConfig(const std::string& scene, const std::vector<std::string>& sets = {}) {
    ConfigOptions options;
    options.configPath = std::string(FOVRT_SOURCE_DIR) + "/presets/thesis-foveated.toml";
    options.ignoredTables = {"experiment"};
    options.overlayTables = {"experiment.quick"};
    // The quick overlay's 3 fps samples 2 s of gaze in 6 frames; per-frame flicker needs the
    // scenes' 30 fps, at which the fovea moves as in the full preset.
    options.sets = {"run.fps=30", "denoise.device=cpu", "scene.name=" + scene};
    options.sets.insert(options.sets.end(), sets.begin(), sets.end());
    ExperimentArgs args;
    args.quick = true;
    return LoadExperiment(options, args).config;
}

}  // namespace fovrt::test
