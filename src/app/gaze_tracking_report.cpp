#include "app/gaze_tracking_report.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "metrics/statistics.h"

namespace fovrt {
GazeTrackingSummary SummarizeGazeTracking(const std::vector<GazeMark>& marks) {
    GazeTrackingSummary s;
    std::vector<double> distances;
    size_t outside = 0;
    for (const GazeMark& m : marks) {
        s.saccadeFrames += m.Saccade() ? 1 : 0;
        if (m.blink) continue;
        distances.push_back(m.foveaDistanceDeg);
        outside += m.outsideFovea ? 1 : 0;
    }
    s.frames = distances.size();
    if (!distances.empty()) {
        const Spread spread = Summarize(distances);
        s.meanDistanceDeg = spread.mean;
        s.medianDistanceDeg = spread.median;
        s.p95DistanceDeg = Quantile(distances, 0.95);
        s.outsideShare = double(outside) / double(distances.size());
    }
    // Each run of saccade frames ends at the next non-saccade frame; recovery = time from there to
    // the first frame (before the next saccade) whose rendered fovea covers the true gaze.
    for (size_t i = 0; i < marks.size(); ++i) {
        if (!marks[i].Saccade() || (i + 1 < marks.size() && marks[i + 1].Saccade())) continue;
        if (i + 1 == marks.size()) break;  // the last frame is a saccade: no landing seen
        const double landed = marks[i + 1].timeSeconds;
        bool recovered = false;
        for (size_t j = i + 1; j < marks.size() && !marks[j].Saccade(); ++j)
            if (!marks[j].blink && !marks[j].outsideFovea) {
                s.recoveryMs.push_back(1000.0 * (marks[j].timeSeconds - landed));
                recovered = true;
                break;
            }
        s.unrecovered += recovered ? 0 : 1;
    }
    return s;
}

std::string GazeTrackingCsv(const std::vector<GazeMark>& marks) {
    std::string out =
        "frame,time_s,blink,gaze_yaw_deg,gaze_pitch_deg,speed_deg_s,saccade,fovea_distance_deg,outside_fovea,gaze_held\n";
    for (const GazeMark& m : marks)
        out += fmt::format("{},{:.9g},{},{:.9g},{:.9g},{:.9g},{},{:.9g},{},{}\n", m.frame, m.timeSeconds, m.blink ? 1 : 0,
                           m.yawDeg, m.pitchDeg, m.speedDegPerSecond, m.Saccade() ? 1 : 0, m.foveaDistanceDeg,
                           m.outsideFovea ? 1 : 0, m.gazeHeld ? 1 : 0);
    return out;
}

std::vector<int> SaccadeFrames(const std::vector<GazeMark>& marks) {
    std::vector<int> frames;
    for (const GazeMark& m : marks)
        if (m.Saccade()) frames.push_back(m.frame);
    return frames;
}

Results WithoutFrames(const Results& results, const std::map<std::string, std::vector<int>>& framesByScene) {
    Results out;
    out.relMseEpsilon = results.relMseEpsilon;
    for (const ResultRow& row : results.rows()) {
        auto it = framesByScene.find(row.scene);
        if (it != framesByScene.end() && std::binary_search(it->second.begin(), it->second.end(), row.frame)) continue;
        out.Add(row);
    }
    return out;
}

nlohmann::json GazeTrackingJson(const GazeTrackingSummary& s, const Results& results, const std::string& scene,
                                const std::vector<GazeMark>& marks) {
    nlohmann::json j;
    j["frames"] = s.frames;
    j["fovea_distance_deg"] = {{"mean", s.meanDistanceDeg}, {"median", s.medianDistanceDeg}, {"p95", s.p95DistanceDeg}};
    j["outside_fovea_share"] = s.outsideShare;
    j["saccade_frames"] = s.saccadeFrames;
    j["saccades"] = s.recoveryMs.size() + s.unrecovered;
    if (s.recoveryMs.empty()) {
        j["recovery_ms"] = {{"mean", nullptr}, {"median", nullptr}, {"max", nullptr}, {"count", 0}};
    } else {
        const Spread recovery = Summarize(s.recoveryMs);
        j["recovery_ms"] = {{"mean", recovery.mean},
                            {"median", recovery.median},
                            {"max", *std::max_element(s.recoveryMs.begin(), s.recoveryMs.end())},
                            {"count", s.recoveryMs.size()}};
    }
    j["unrecovered"] = s.unrecovered;
    const std::vector<int> saccades = SaccadeFrames(marks);
    const std::set<int> saccadeSet(saccades.begin(), saccades.end());
    nlohmann::json split = nlohmann::json::object();
    for (const std::string& variant : results.Variants(scene)) {
        std::vector<double> fixation, saccade;
        for (const auto& [frame, value] : results.PerFrame(scene, variant, "fovea", "relmse"))
            (saccadeSet.count(frame) ? saccade : fixation).push_back(value);
        auto mean = [](const std::vector<double>& v) -> nlohmann::json {
            if (v.empty()) return nullptr;
            return Summarize(v).mean;
        };
        split[variant] = {{"fixation", mean(fixation)}, {"saccade", mean(saccade)},
                          {"fixation_frames", fixation.size()}, {"saccade_frames", saccade.size()}};
    }
    j["foveal_relmse"] = split;
    return j;
}

std::string GazeTrackingTable(const nlohmann::json& j, const std::string& scene) {
    // A missing value (no saccade, no frames of a kind) is null in the JSON and "-" here.
    auto number = [](const nlohmann::json& v, int decimals) {
        return v.is_number() ? fmt::format("{:.{}f}", v.get<double>(), decimals) : std::string("-");
    };
    const nlohmann::json& distance = j["fovea_distance_deg"];
    std::string out = fmt::format(
        "Gaze tracking, {}: rendered fovea to true gaze {}° mean, {}° median, {}° p95; true gaze outside the "
        "rendered fovea in {} % of {} frames\n",
        scene, number(distance["mean"], 2), number(distance["median"], 2), number(distance["p95"], 2),
        number(100.0 * j["outside_fovea_share"].get<double>(), 1), j["frames"].get<size_t>());
    const nlohmann::json& recovery = j["recovery_ms"];
    out += fmt::format("  {} saccades ({} frames): the rendered fovea covers the gaze again after {} ms mean, {} ms "
                       "median, {} ms max; {} not covered before the next\n",
                       j["saccades"].get<size_t>(), j["saccade_frames"].get<size_t>(), number(recovery["mean"], 1),
                       number(recovery["median"], 1), number(recovery["max"], 1), j["unrecovered"].get<size_t>());
    for (const auto& [variant, split] : j["foveal_relmse"].items())
        out += fmt::format("  {:<18} foveal relMSE: fixation frames {}, saccade frames {}\n", variant,
                           number(split["fixation"], 5), number(split["saccade"], 5));
    return out;
}

}  // namespace fovrt
