// Summaries of per-frame metric values that a researcher can trust (issue #16): robust
// location (mean, median, geometric mean), the paired per-frame ratio of a variant against a
// baseline with a moving-block bootstrap confidence interval, the win rate, and the frames that
// dominate a mean. Pure functions of their inputs: no I/O, a fixed RNG seed, so the same values
// give the same interval on every run and machine.
//
// Method (stated in every report; see ComparePaired):
//   - The values of one variant are paired with the baseline's on the same (seed, eye, frame):
//     both saw identical noisy inputs. d_t = ln(variant_t / baseline_t); the ratio is exp(mean d),
//     the geometric mean of the per-frame ratios (a frame 100× worse than the others counts as
//     one frame, not as the whole mean). Pairs with a non-positive or non-finite value are dropped
//     and counted.
//   - Frames are correlated in time (the denoisers' histories, the gaze path), so the interval
//     comes from a circular moving-block bootstrap (Politis & Romano 1992): each (seed, eye)
//     sequence of d_t is resampled on its own by concatenating blocks of `b` consecutive frames
//     (wrapping at the end) from uniform random starts, cut to the sequence's length; the pooled
//     mean of all resampled sequences is one replicate. Sequences are never mixed, so the
//     independence of seeds and the pairing of eyes within a frame are kept.
//   - b is chosen from the data's autocorrelation with the rule of Politis & White (2004, with
//     the correction of Patton, Politis & White 2009) for the circular bootstrap, on the pooled
//     autocovariance of the sequences, clamped to [1, ceil(min(3√n, n/3))]; iid data gives b ≈ 1.
//   - The interval is the percentile interval of exp(replicate) (2,000 replicates, 95 %).
//     A difference is significant when the interval excludes 1 (no change).
//   - Win rate: the fraction of pairs in which the variant is better (lower error, or higher for a
//     similarity such as SSIM); ties count one half. Values within kTieTolerance (relative) of
//     each other are a tie with log ratio 0: the metrics are means of float maps, and a
//     difference in their last bits is not a difference between denoisers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fovrt {

// Location of a set of values. NaNs are skipped. geometricMean is NaN when any value is ≤ 0.
struct Spread {
    double mean = 0.0;
    double median = 0.0;
    double geometricMean = 0.0;
    size_t count = 0;
};
Spread Summarize(const std::vector<double>& values);

inline constexpr double kTieTolerance = 1e-6;

// Which direction of a metric is better.
enum class Better { kLower, kHigher };

// One (seed, eye) sequence of consecutive frames: the baseline's and the variant's value per
// frame, same length, same order.
struct PairedSequence {
    std::vector<double> baseline;
    std::vector<double> variant;
};

struct BootstrapOptions {
    int resamples = 2000;
    double confidence = 0.95;
    uint64_t rngSeed = 0x5eedb007;  // fixed: reports are reproducible
    int blockLength = 0;            // 0: automatic (Politis & White); 1: iid resampling of frames
};

struct PairedRatio {
    double ratio = 1.0;  // geometric mean of per-frame variant/baseline
    double lower = 1.0;  // bootstrap interval of the ratio
    double upper = 1.0;
    double winRate = 0.0;  // fraction of pairs where the variant is better, ties 1/2
    size_t pairs = 0;      // pairs used
    size_t dropped = 0;    // pairs with a value ≤ 0 or non-finite
    int blockLength = 1;   // frames per bootstrap block
    // The interval excludes 1 (and there are pairs).
    bool Significant() const { return pairs > 0 && (upper < 1.0 || lower > 1.0); }
};
PairedRatio ComparePaired(const std::vector<PairedSequence>& sequences, Better better,
                          const BootstrapOptions& options = {});

// The automatic block length of the circular block bootstrap (Politis & White 2004, Patton et
// al. 2009) from the autocovariance pooled over the sequences (each demeaned on its own).
int AutomaticBlockLength(const std::vector<std::vector<double>>& sequences);

// `resamples` replicates of the pooled mean of the sequences, each sequence resampled by the
// circular block bootstrap with blocks of `blockLength` frames (1 = iid).
std::vector<double> BlockBootstrapMeans(const std::vector<std::vector<double>>& sequences,
                                        int blockLength, int resamples, uint64_t rngSeed);

// Value of the sorted sample at quantile q in [0, 1] (linear interpolation, type 7).
double Quantile(std::vector<double> values, double q);

// The smallest set of the largest values whose sum is at least `fraction` of the total (all
// values ≥ 0; NaNs ignored): their indices, largest first, and the share of the sum they hold.
struct DominantSet {
    std::vector<size_t> indices;
    double share = 0.0;
};
DominantSet DominantValues(const std::vector<double>& values, double fraction = 0.5);

}  // namespace fovrt
