// ExperimentStats: the statistics of an experiment's Results (metrics/statistics.h applied per
// scene × variant × region × metric), computed once and read by summary.json, the stdout table
// and the HTML report. No I/O.
//
//   - spread: mean, median and geometric mean of every per-frame value (frames × eyes × seeds);
//   - vsBaseline (whole, fovea and periphery, every variant but the baseline): the paired
//     per-frame ratio to the baseline with its block-bootstrap interval and the win rate, pairs
//     matched on (seed, eye, frame), one bootstrap sequence per (seed, eye);
//   - dominant: the frames (per-frame value averaged over eyes and seeds) that hold half of the
//     sum behind the mean, named when they are at most a fifth of the frames.
// Which direction is better: lower for errors (relmse, flip, temporal), higher for ssim.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "app/report.h"
#include "metrics/statistics.h"

namespace fovrt {

// The regions that get a paired comparison (eccentricity bands: spread only).
inline const std::vector<std::string>& ComparedRegions() {
    static const std::vector<std::string> regions = {"whole", "fovea", "periphery"};
    return regions;
}

Better BetterOf(const std::string& metric);

// The frames that dominate a mean: `frames` (largest first) hold `share` of the sum over
// `totalFrames` frames.
struct DominantFrames {
    std::vector<int> frames;
    double share = 0.0;
    size_t totalFrames = 0;
    // At most a fifth of the frames (and at least 5 frames in all) hold half of the mean.
    bool Dominates() const { return totalFrames >= 5 && !frames.empty() && frames.size() * 5 <= totalFrames; }
};

struct MetricStats {
    Spread spread;
    std::optional<PairedRatio> vsBaseline;
    DominantFrames dominant;
};

// The shape of one scene's data.
struct SceneDesign {
    std::vector<uint32_t> seeds;
    size_t frames = 0;  // distinct frames
    size_t eyes = 0;    // distinct eyes
    std::string baseline;
};

class ExperimentStats {
public:
    // `baseline`: the requested baseline variant ("" = each scene's first variant).
    explicit ExperimentStats(const Results& results, const std::string& baseline = "",
                             const BootstrapOptions& options = {});

    const std::vector<std::string>& Scenes() const { return scenes_; }
    const SceneDesign& Design(const std::string& scene) const { return designs_.at(scene); }
    const MetricStats* Find(const std::string& scene, const std::string& variant, const std::string& region,
                            const std::string& metric) const;
    const BootstrapOptions& Options() const { return options_; }
    // Smallest and largest block length over every comparison (1, 1 when there is none).
    std::pair<int, int> BlockLengthRange() const;

private:
    BootstrapOptions options_;
    std::vector<std::string> scenes_;
    std::map<std::string, SceneDesign> designs_;
    std::map<std::tuple<std::string, std::string, std::string, std::string>, MetricStats> stats_;
};

// The method in words, for the report, the table and summary.json.
std::string StatisticsMethod(const BootstrapOptions& options);

}  // namespace fovrt
