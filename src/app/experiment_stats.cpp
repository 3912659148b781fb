#include "app/experiment_stats.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

namespace fovrt {

namespace {

// (seed, eye) -> frame -> value: one cell's per-frame values, in time order per sequence.
using Sequences = std::map<std::pair<uint32_t, int>, std::map<int, double>>;
using CellKey = std::tuple<std::string, std::string, std::string, std::string>;  // scene, variant, region, metric

DominantFrames Dominant(const Sequences& cell) {
    std::map<int, std::pair<double, int>> byFrame;  // mean over eyes and seeds
    for (const auto& [sequence, frames] : cell)
        for (const auto& [frame, value] : frames)
            if (!std::isnan(value)) {
                byFrame[frame].first += value;
                byFrame[frame].second += 1;
            }
    std::vector<int> frames;
    std::vector<double> means;
    for (const auto& [frame, acc] : byFrame) {
        frames.push_back(frame);
        means.push_back(std::max(0.0, acc.first / acc.second));
    }
    DominantFrames d;
    d.totalFrames = frames.size();
    DominantSet set = DominantValues(means, 0.5);
    for (size_t i : set.indices) d.frames.push_back(frames[i]);
    d.share = set.share;
    return d;
}

}  // namespace

Better BetterOf(const std::string& metric) { return metric == "ssim" ? Better::kHigher : Better::kLower; }

ExperimentStats::ExperimentStats(const Results& results, const std::string& baseline, const BootstrapOptions& options)
    : options_(options), scenes_(results.Scenes()) {
    std::map<CellKey, Sequences> cells;
    std::map<std::string, std::set<int>> frames, eyes;
    for (const ResultRow& r : results.rows()) {
        cells[{r.scene, r.variant, r.region, r.metric}][{r.seed, r.eye}][r.frame] = r.value;
        frames[r.scene].insert(r.frame);
        eyes[r.scene].insert(r.eye);
    }
    for (const std::string& scene : scenes_) {
        SceneDesign& design = designs_[scene];
        design.seeds = results.Seeds(scene);
        design.frames = frames[scene].size();
        design.eyes = eyes[scene].size();
        design.baseline = BaselineOf(results, scene, baseline);
    }
    for (const auto& [key, cell] : cells) {
        const auto& [scene, variant, region, metric] = key;
        MetricStats stats;
        std::vector<double> all;
        for (const auto& [sequence, values] : cell)
            for (const auto& [frame, value] : values) all.push_back(value);
        stats.spread = Summarize(all);
        stats.dominant = Dominant(cell);
        const std::string& base = designs_[scene].baseline;
        auto baseCell = cells.find({scene, base, region, metric});
        const bool compared = std::find(ComparedRegions().begin(), ComparedRegions().end(), region) !=
                              ComparedRegions().end();
        if (variant != base && compared && baseCell != cells.end()) {
            // Pairs on (seed, eye, frame): a frame only one of the two has is left out.
            std::vector<PairedSequence> paired;
            for (const auto& [sequence, values] : cell) {
                auto baseSequence = baseCell->second.find(sequence);
                if (baseSequence == baseCell->second.end()) continue;
                PairedSequence p;
                for (const auto& [frame, value] : values) {
                    auto b = baseSequence->second.find(frame);
                    if (b == baseSequence->second.end()) continue;
                    p.baseline.push_back(b->second);
                    p.variant.push_back(value);
                }
                if (!p.baseline.empty()) paired.push_back(std::move(p));
            }
            stats.vsBaseline = ComparePaired(paired, BetterOf(metric), options_);
        }
        stats_.emplace(key, std::move(stats));
    }
}

const MetricStats* ExperimentStats::Find(const std::string& scene, const std::string& variant,
                                         const std::string& region, const std::string& metric) const {
    auto it = stats_.find({scene, variant, region, metric});
    return it == stats_.end() ? nullptr : &it->second;
}

std::pair<int, int> ExperimentStats::BlockLengthRange() const {
    int lo = 0, hi = 0;
    for (const auto& [key, stats] : stats_)
        if (stats.vsBaseline && stats.vsBaseline->pairs > 0) {
            const int b = stats.vsBaseline->blockLength;
            lo = lo == 0 ? b : std::min(lo, b);
            hi = std::max(hi, b);
        }
    return lo == 0 ? std::pair{1, 1} : std::pair{lo, hi};
}

std::string StatisticsMethod(const BootstrapOptions& options) {
    return fmt::format(
        "Every value is one (seed, eye, frame). Mean, median and geometric mean are over all of them. "
        "Against the baseline, each value is paired with the baseline's on the same seed, eye and frame "
        "(identical noisy inputs); ratio = geometric mean of the per-frame ratios variant/baseline "
        "(exp of the mean log ratio; a pair with a value <= 0 is dropped). Its {:g} % interval is the "
        "percentile interval of a circular moving-block bootstrap ({} resamples, RNG seed {:#x}): each "
        "(seed, eye) sequence of log ratios is resampled on its own from blocks of b consecutive frames, "
        "b chosen from the autocorrelation of the log ratios by the rule of Politis & White (2004, "
        "corrected by Patton et al. 2009) and clamped to [1, min(3 sqrt(n), n/3)]; b = 1 is iid resampling. "
        "A difference whose interval contains 1 (no change) is marked not significant (ns). Win rate: the "
        "share of pairs in which the variant is better (lower error; higher SSIM), ties (a relative difference "
        "below 1e-6, float noise) counted half and as ratio 1.",
        100.0 * options.confidence, options.resamples, options.rngSeed);
}

}  // namespace fovrt
