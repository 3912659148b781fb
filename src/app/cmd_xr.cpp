// `fovrt xr`: a headset session through OpenXR (SPEC §11). Every config key and --set works as in
// `run`; camera.width/height are the headset's recommended size.
#include <memory>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "app/shared_options.h"
#include "config/config_cli.h"
#include "core/error.h"
#include "xr/xr_app.h"

namespace fovrt {

void RegisterXrCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "xr", "Headset session through OpenXR: eye-tracked (or configured) gaze -> foveated path tracing -> "
              "denoising on the runtime's Vulkan device -> each eye's swapchain");
    auto config = std::make_shared<ConfigOptions>();
    auto options = std::make_shared<XrOptions>();
    auto window = std::make_shared<std::string>("960x540");
    AddConfigOptions(cmd, *config);
    AddLiveSessionOptions(cmd, options->session);
    cmd->add_option("--frames", options->frames,
                    "render N frames, then end the session through xrRequestExitSession (0: until Ctrl-C or "
                    "the runtime stops)");
    cmd->add_flag("--write-frames", options->writeFrames,
                  "write what each eye was sent, as PNG, to <output.dir>/xr/frames");
    cmd->add_flag("--follow-path", options->followPath,
                  "the scene camera's path carries the headset's origin (default: its start pose)");
    cmd->add_option("--speed", options->speed, "scene seconds per second of display time")
        ->check(CLI::NonNegativeNumber);
    cmd->add_flag("--async", options->async,
                  "render on a thread of its own and submit the newest frame at every display slot (the "
                  "compositor reprojects it); default: one frame rendered per xrBeginFrame/xrEndFrame");
    cmd->add_flag("--mirror", options->mirror, "show what the headset gets in a desktop window, with the panel");
    cmd->add_option("--window", *window, "mirror window size WxH");
    cmd->add_option("--screenshot", options->screenshot,
                    "with --mirror and --frames: write the mirror window's last image (PNG)");
    cmd->callback([config, options, window] {
        XrOptions o = *options;
        ParseWindowSize(*window, o.window);
        o.window.title = "fovrt xr mirror";
        if (!o.screenshot.empty() && (!o.mirror || o.frames == 0)) Fail("--screenshot needs --mirror and --frames N");
        RunXr(ResolveConfig(*config), o);
    });
}

}  // namespace fovrt
