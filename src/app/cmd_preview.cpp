// `fovrt preview`: the desktop mirror window of a live session (SPEC §11). Every config key and
// --set works as in `run`; the options here are the window's.
#include <memory>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "app/shared_options.h"
#include "config/config_cli.h"
#include "core/error.h"
#include "preview/preview_app.h"

namespace fovrt {

void RegisterPreviewCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "preview", "Live session in a desktop window: gaze (mouse or synthetic) -> foveated path tracing -> "
                   "denoising on Vulkan -> both eyes on screen, with a control panel");
    auto config = std::make_shared<ConfigOptions>();
    auto options = std::make_shared<PreviewOptions>();
    auto layout = std::make_shared<std::string>("both");
    auto window = std::make_shared<std::string>("960x540");
    auto noOverlay = std::make_shared<bool>(false);
    auto noPanel = std::make_shared<bool>(false);
    AddConfigOptions(cmd, *config);
    AddLiveSessionOptions(cmd, options->session);
    cmd->add_option("--frames", options->frames,
                    "render N frames, show the last, exit (0: until the window closes)");
    cmd->add_option("--screenshot", options->screenshot,
                    "with --frames: write the last presented window image (PNG, the swapchain's pixels)");
    cmd->add_option("--linger", options->lingerSeconds,
                    "with --frames: keep showing the last frame this many seconds before exiting");
    cmd->add_option("--capture-dir", options->captureDir, "where F12 saves (default <output.dir>/captures)");
    cmd->add_option("--layout", *layout, "both | left | right (one eye enlarged)")
        ->check(CLI::IsMember({"both", "left", "right"}));
    cmd->add_option("--window", *window, "window size WxH");
    cmd->add_flag("--no-overlay", *noOverlay, "start without the gaze marker and fovea outline");
    cmd->add_flag("--no-panel", *noPanel, "start without the control panel (Tab shows it)");
    cmd->add_flag("--vsync", options->window.vsync, "present with FIFO (default: mailbox/immediate)");
    cmd->add_flag("--pipelined", options->pipelined,
                  "trace frame N+1 while denoising N: more frames/s where the stages use different "
                  "processors (a GPU denoiser); on a 2-core CPU with lavapipe it is slower");
    cmd->add_option("--fly-speed", options->flySpeed, "free camera speed, metres per second");
    cmd->callback([config, options, layout, window, noOverlay, noPanel] {
        PreviewOptions o = *options;
        o.layout = *layout == "left"    ? DisplayLayout::LeftEye
                   : *layout == "right" ? DisplayLayout::RightEye
                                        : DisplayLayout::SideBySide;
        ParseWindowSize(*window, o.window);
        o.overlay = !*noOverlay;
        o.panel = !*noPanel;
        if (!o.screenshot.empty() && o.frames == 0) Fail("--screenshot needs --frames N");
        RunPreview(ResolveConfig(*config), o);
    });
}

}  // namespace fovrt
