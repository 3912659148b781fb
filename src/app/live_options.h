// The command-line options `fovrt preview` and `fovrt xr` share: the ones LiveSessionWiring
// (live/live_session.h) acts on, declared once so both commands spell and explain them alike.
#pragma once

#include <CLI/CLI.hpp>

#include "live/live_session.h"

namespace fovrt {

// --view, --write-inputs, --record, --stats into `options`.
void AddLiveSessionOptions(CLI::App* command, LiveSessionOptions& options);

}  // namespace fovrt
