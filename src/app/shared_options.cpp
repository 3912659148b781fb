#include "app/shared_options.h"

namespace fovrt {

void AddLiveSessionOptions(CLI::App* command, LiveSessionOptions& options) {
    command->add_option("--view", options.view,
                        "the view shown first: denoised | noisy | spp | albedo | normal | depth | error | a "
                        "denoiser's own view");
    command->add_flag("--write-inputs", options.writeInputs,
                      "write every frame's FrameInputs + spp map EXRs to <output.dir>/inputs (as `run`)");
    command->add_option("--record", options.record,
                        "record the session (head pose, both eyes' cameras, gaze samples, config; JSON Lines) "
                        "for `run --replay`");
    command->add_option("--stats", options.stats, "per-frame timings and latency, JSON Lines");
}

void AddReplayOptions(CLI::App* command, std::string& replay, bool& allowChanges) {
    command->add_option("--replay", replay,
                        "Render a session recording's frames (its scene, cameras and gaze; its config with "
                        "-c/--set on top) instead of the scene's path");
    command->add_flag("--allow-changes", allowChanges,
                      "With --replay: accept config changes that make the frames differ from the recording");
}

}  // namespace fovrt
