// Replaying session recordings (session/session_record.h) headless, and recording headless runs:
// `fovrt run --replay FILE`, `fovrt experiment FILE --replay REC`, `fovrt run --record FILE`.
//
// The config of a replay is the recording's (its header), with the command's -c FILE and --set on
// top. Each differing key is one of:
//   free      no effect on the noisy frames: denoise.* (see below), output.*, reference.*,
//             run.threads, memory_budget. Taken from the command.
//   supplied  the recording carries it: gaze.* (the recorded gaze), camera.fov_deg and camera.ipd
//             (each recorded eye's FOV and position), run.frames and run.first_frame (every
//             recorded frame is rendered), run.fps (each frame's scene time). The recording's value
//             is kept and a note names the ignored keys.
//   changes   would change the frames: camera.width and camera.height (the recorded eyes rendered
//             at that size, same pose and FOV), run.seed, run.max_depth, foveation.*, a
//             denoise.denoisers list that adds or drops A-SVGF gradient samples (they replace
//             noisy samples), and any key not listed here. Refused with one line naming the key,
//             unless --allow-changes: then rendered, noted, and listed in the manifest.
//   refused   scene.*: the recorded poses belong to the recorded scene. Also refused: a scene
//             whose content fingerprint differs from the one in the header (its files changed),
//             unless --allow-changes.
// Without changes a replay renders bit-identical spp maps and noisy FrameInputs to the session.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/config.h"
#include "pipeline/frame_pipeline.h"
#include "session/session_record.h"

namespace fovrt {

struct ConfigOptions;  // config/config_cli.h

// A recording checked end to end (every frame read and validated before anything is written).
struct Replay {
    std::filesystem::path file;
    nlohmann::json header;
    RunConfig recorded;      // the header's config
    SessionSummary summary;  // frame count, first and last index
    // Filled by ResolveReplayConfig: the keys whose config value was ignored (supplied by the
    // recording) and those that change the frames (only with allowChanges), as
    // {"key", "value", "recorded"}.
    std::vector<std::string> ignored;
    nlohmann::json changed = nlohmann::json::array();
    bool allowChanges = false;

    // For the run manifest: file, frames, first/last frame, ignored and changed keys.
    nlohmann::json ToJson() const;
};

// Reads the header and every frame of `file` (fovrt::Error, one line, for anything corrupt).
Replay OpenReplay(const std::filesystem::path& file, bool allowChanges);

// The job's config for a replay: options.base = the recording's config, resolved with
// `resolve` (ResolveConfig or the experiment's), then reconciled with the recording as described
// above. Prints one note on stderr (prefixed `command`) for ignored keys and one for changes.
// Throws fovrt::Error naming the key of a refused change.
RunConfig ResolveReplayConfig(Replay& replay, ConfigOptions options,
                              const std::function<RunConfig(const ConfigOptions&)>& resolve,
                              const std::string& command);

// The config a FramePipeline for a replay is built with: the recorded gaze replaces the gaze
// source, so the source is a static one that is never asked (a recorded trace file need not
// exist where the recording is replayed).
RunConfig ReplayPipelineConfig(RunConfig config);

// Refuses (fovrt::Error naming the file) a scene whose content fingerprint differs from the
// header's, unless replay.allowChanges (then noted and listed in replay.changed).
void CheckReplayScene(Replay& replay, const FramePipeline& pipeline);

// The header members fovrt adds to a recording besides the config: build info and the scene's
// name, source and content fingerprint (replays refuse a scene whose files changed).
nlohmann::json SessionHeaderExtra(const FramePipeline& pipeline);

// The frames a job renders, in order: the config's frames (run.first_frame, run.frames; head and
// eyes from the scene's camera path, gaze from the gaze source) or a recording's.
// The last frame a job renders: run.first_frame + run.frames − 1, or the recording's last.
uint32_t LastFrameOf(const RunConfig& config, const Replay* replay);

class FrameSequence {
public:
    // Headless frames of `pipeline`'s config: run.warmup_frames before run.first_frame, then
    // run.frames from it.
    explicit FrameSequence(const FramePipeline& pipeline);
    // A recording's frames, rendered at config.camera's size (the recorded eyes resized when the
    // config changed it).
    FrameSequence(const FramePipeline& pipeline, const Replay& replay);

    // The next frame (request, head pose, gaze samples); false after the last.
    bool Next(RecordedFrame& out);
    int Count() const { return count_; }  // warm-up included
    int Scored() const { return count_ - warmup_; }  // the frames from run.first_frame on
    uint32_t LastFrame() const { return lastFrame_; }

private:
    const FramePipeline& pipeline_;
    std::unique_ptr<SessionReader> reader_;  // null: headless
    int first_ = 0;   // headless: the first frame, warm-up included
    int warmup_ = 0;  // headless: run.warmup_frames
    int count_ = 0;
    int next_ = 0;
    uint32_t lastFrame_ = 0;
    int width_ = 0, height_ = 0;
};

}  // namespace fovrt
