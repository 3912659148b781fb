// fovrt: foveated VR path-tracing testbed. One executable, one subcommand per workflow.
#include <cstdio>
#include <exception>
#include <new>

#include <CLI/CLI.hpp>

#include "commands.h"
#include "core/error.h"
#include "core/interrupt.h"

int main(int argc, char** argv) {
    CLI::App app{"fovrt: foveated VR path-tracing testbed (stereo Embree tracer, foveated spp maps, "
                 "SVGF / A-SVGF / two-history SVGF on Vulkan compute)"};
    app.require_subcommand(1);
    // In the order `fovrt --help` lists them.
    using namespace fovrt;
    for (auto registerCommand : {RegisterRunCommand, RegisterReferenceCommand, RegisterDatasetCommand,
                                 RegisterExperimentCommand, RegisterRaysSavedCommand, RegisterClusterCommand,
                                 RegisterInfoCommand, RegisterConfigCommand, RegisterBenchCommand,
                                 RegisterMemoryCommand, RegisterVdpCommand, RegisterPreviewCommand, RegisterXrCommand})
        registerCommand(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const fovrt::Interrupted& e) {
        std::fprintf(stderr, "fovrt: %s\n", e.what());
        return e.ExitCode();
    } catch (const fovrt::Error& e) {
        std::fprintf(stderr, "fovrt: error: %s\n", e.what());
        return 1;
    } catch (const std::bad_alloc&) {
        // An allocation outside the planes (those name their size: core/image.h).
        std::fprintf(stderr, "fovrt: error: out of memory (an allocation failed; lower camera.width / "
                             "camera.height, or give --memory-budget to refuse before rendering)\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fovrt: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
