// Rays saved between sampling designs that ran in separate sweeps (`fovrt rays-saved RUN...`): the
// runs' curves.csv rows gathered into one set of curves, then the delta, the intervals and the
// per-point savings a single sweep prints (app/sweep_outputs.h), so that a design added later is
// measured against the anchor's points of an earlier run without running them again.
//
// Runs are gathered only where they score the same thing; anything else is refused in one line
// naming the runs and what differs:
//   - each run is a finished sweep: manifest.json complete, curves.csv and summary.json present;
//   - the same config but for the output folder (manifest.json "config": the eye, frames, gaze,
//     references, denoiser settings, the fovea the errors are taken in);
//   - the same content wherever a scene was loaded, in every point of every run (each point's
//     designs/<label>/manifest.json: the scene's fingerprint), so a scene file changed between
//     two runs is caught although their configs are equal;
//   - the same keys wherever two runs name the same design (summary.json);
//   - the same scores wherever two runs hold the same point (scene, variant, design, budget, seed),
//     to the last digit: the sweep is deterministic, so a difference means a different build or
//     input; the measured rays to 1 % (they are a mean over the run's seeds, which may differ).
// A curve takes the seeds every one of its points and the anchor's hold (the paired bootstrap's
// unit); the seeds each comparison used are reported with it.
//
// Pooled gaze (`--pool-gaze`): runs may also differ in where the eye looks, the keys of
// GazeParams (gaze/gaze_source.h: the source, its recording or trace and start, a static direction,
// a Lissajous path), never in the tracker's. Each distinct gaze is a window, and each (window,
// seed) a unit of the bootstrap: the curves average every unit's JOD at each budget, and the
// interval spans where the eye looked as well as the seeds.
#pragma once

#include <compare>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/sweep_outputs.h"

namespace fovrt {

// One row of a run's curves.csv: a (scene, variant, design, budget, seed) and what it measured.
struct CurveRow {
    std::string scene, variant, design;
    std::string budget;  // as written ("" for a design at its own sampling)
    uint32_t seed = 0;
    size_t window = 0;  // index into GatheredCurves::windows: where the eye looked
    double tracedWhole = 0.0, tracedFovea = 0.0, tracedPeriphery = 0.0, guideRays = 0.0;
    double jod = 0.0, jodSustained = 0.0, jodTransient = 0.0;
    double relmseWhole = 0.0, relmseFovea = 0.0, flickerFovea = 0.0;
    size_t run = 0;  // index into GatheredCurves::runs: the first run that holds it
};

// The rows of several runs, each point, window and seed once.
struct GatheredCurves {
    std::vector<std::filesystem::path> runs;
    std::vector<CurveRow> rows;
    // Each window's gaze keys that differ between the windows ("gaze.trace_start_ms=9000"), ordered
    // by those keys (numbers by value), whatever the runs' order; one empty entry when every run
    // shares its gaze.
    std::vector<std::string> windows;
};

enum class GazeWindows { kSame, kPooled };

// Reads and checks the runs (output folders of `fovrt experiment` sweeps), in the order given.
GatheredCurves GatherSweepRuns(const std::vector<std::filesystem::path>& runs, GazeWindows gaze = GazeWindows::kSame);

// Keeps the rows at these budgets (spp, as numbers) and those of designs at their own sampling,
// so that runs with different budget lists compare on the budgets they share (a comparison takes
// only the units every one of its points holds). Refuses a budget no row holds.
void KeepBudgets(GatheredCurves& curves, const std::vector<double>& budgets);

// A unit of the bootstrap: a seed in one window.
struct SampleUnit {
    size_t window = 0;
    uint32_t seed = 0;
    auto operator<=>(const SampleUnit&) const = default;
};

// One comparison: a design against the anchor on one (scene, variant), with the units it used.
struct DesignComparison {
    RaysSavedRow saved;
    std::vector<SampleUnit> units;
    std::vector<std::string> budgets;  // the design's points, rays ascending
    std::vector<double> rays, jod;     // per point: measured rays, mean JOD over `units`
};
// Every design in `designs` (empty: every design but the anchor) against `anchor`, per scene and
// variant both hold. Refuses an anchor or design no run holds.
std::vector<DesignComparison> CompareDesigns(const GatheredCurves& curves, const std::string& anchor,
                                             const std::vector<std::string>& designs);

// The headline table and each design's points with the rays saved at each, as text; with several
// windows, each window's gaze and the units are named (w1:2: window 1, seed 2).
std::string DesignComparisonText(const std::string& anchor, const std::vector<DesignComparison>& comparisons,
                                 const std::vector<std::string>& windows = {});

// The same comparisons as JSON, every figure unrounded: the anchor, the runs and windows, and per
// comparison its scene, variant, design, units (with the bootstrap's unit: "seed", or "window
// and seed" over pooled gaze windows), rays saved, JOD gain and rays saved at equal
// foveal relMSE (IntervalJson) and each point's budget, measured rays, mean JOD and rays saved
// at its JOD: what `fovrt rays-saved --json` writes.
nlohmann::json DesignComparisonJson(const std::string& anchor, const std::vector<DesignComparison>& comparisons,
                                    const GatheredCurves& curves);

// With several windows: each window's comparisons on its own rows, one line per (window, scene,
// variant, design), so that how the pooled saving spreads over where the eye looked is read off
// the same command. Empty with one window.
std::string PerWindowText(const GatheredCurves& curves, const std::string& anchor,
                          const std::vector<std::string>& designs);

}  // namespace fovrt
