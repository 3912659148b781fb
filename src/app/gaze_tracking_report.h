// What the eye tracker did to an experiment, beside the errors: per frame the angle between the
// rendered fovea (the tracked gaze) and the true gaze and whether the true gaze fell outside the
// rendered fovea disc; per scene the share of such misses, the time after each saccade until the
// rendered fovea covers the gaze again, and each variant's foveal error split into saccade and
// fixation frames. Saccade frames are those of the report's gaze marks (I-VT on the true gaze,
// kSaccadeDegPerSecond); the marks come from the report's eye under the first seed (the gaze does
// not depend on the run seed).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/report.h"
#include "app/report_html.h"

namespace fovrt {

struct GazeTrackingSummary {
    size_t frames = 0;  // frames with a valid true gaze (the distances' count)
    double meanDistanceDeg = 0.0, medianDistanceDeg = 0.0, p95DistanceDeg = 0.0;
    double outsideShare = 0.0;        // of `frames`: the true gaze outside the rendered fovea
    size_t saccadeFrames = 0;
    std::vector<double> recoveryMs;   // per saccade: from its first fixation frame to the first frame
                                      // whose rendered fovea covers the gaze (0: covered at once)
    size_t unrecovered = 0;           // saccades not covered again before the next one or the end
};
GazeTrackingSummary SummarizeGazeTracking(const std::vector<GazeMark>& marks);

// Per-frame CSV: frame,time_s,blink,speed_deg_s,saccade,fovea_distance_deg,outside_fovea,gaze_held
// (gaze_held: the frame lies past the end of its trace or recording, gaze.trace_end = "hold").
std::string GazeTrackingCsv(const std::vector<GazeMark>& marks);

// The frames of `marks` that are saccades.
std::vector<int> SaccadeFrames(const std::vector<GazeMark>& marks);
// `results` without the rows of the saccade frames of each scene (experiment.suppress_saccades:
// vision is suppressed during a saccade, so its errors are not seen).
Results WithoutFrames(const Results& results, const std::map<std::string, std::vector<int>>& framesByScene);

// {"frames", "fovea_distance_deg": {"mean", "median", "p95"}, "outside_fovea_share",
//  "saccade_frames", "saccades", "recovery_ms": {"mean", "median", "max"}, "unrecovered",
//  "foveal_relmse": {variant: {"fixation", "saccade"}}} for one scene.
nlohmann::json GazeTrackingJson(const GazeTrackingSummary& summary, const Results& results, const std::string& scene,
                                const std::vector<GazeMark>& marks);
// The same as lines for the stdout table.
std::string GazeTrackingTable(const nlohmann::json& sceneJson, const std::string& scene);

}  // namespace fovrt
