// FrameRequest: what one stereo frame is rendered from. Its own header so that session
// recordings (session/session_record.h) and the frame pipeline share it without depending on each
// other.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "core/camera.h"
#include "gaze/gaze_source.h"

namespace fovrt {

// What one stereo frame is rendered from. Headless runs take it from the scene's camera path and
// the configured gaze source (FramePipeline::RequestAt); a live session builds it from the window
// or headset, and a recording replays it (src/session/session_record.h).
struct FrameRequest {
    uint32_t frame = 0;        // sequential index: seeds the sampler; not frame+1 = camera cut
    double timeSeconds = 0.0;  // scene time (animation)
    std::array<EyeCamera, 2> eyes;
    GazeSample gaze;           // head space: the gaze the spp maps follow (the tracker's)
    // Where the eye really was (head space), when it differs from `gaze` (a modelled tracker,
    // gaze/tracker.h); the metrics follow it. Unset: the eye was where `gaze` says.
    std::optional<GazeSample> trueGaze;
    const GazeSample& EyeGaze() const { return trueGaze ? *trueGaze : gaze; }
};

}  // namespace fovrt
