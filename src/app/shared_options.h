// Command-line options more than one command takes, declared once so the commands spell and
// explain them alike: the live-session ones LiveSessionWiring (live/live_session.h) acts on, for
// `fovrt preview` and `fovrt xr`; the replay ones (app/replay.h), for `fovrt run` and
// `fovrt experiment`.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "live/live_session.h"

namespace fovrt {

// --view, --write-inputs, --record, --stats into `options`.
void AddLiveSessionOptions(CLI::App* command, LiveSessionOptions& options);

// --replay FILE and --allow-changes.
void AddReplayOptions(CLI::App* command, std::string& replay, bool& allowChanges);

}  // namespace fovrt
