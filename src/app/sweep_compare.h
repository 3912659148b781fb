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
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "app/sweep_outputs.h"

namespace fovrt {

// One row of a run's curves.csv: a (scene, variant, design, budget, seed) and what it measured.
struct CurveRow {
    std::string scene, variant, design;
    std::string budget;  // as written ("" for a design at its own sampling)
    uint32_t seed = 0;
    double tracedWhole = 0.0, tracedFovea = 0.0, tracedPeriphery = 0.0, guideRays = 0.0;
    double jod = 0.0, jodSustained = 0.0, jodTransient = 0.0;
    double relmseWhole = 0.0, relmseFovea = 0.0, flickerFovea = 0.0;
    size_t run = 0;  // index into GatheredCurves::runs: the first run that holds it
};

// The rows of several runs, each point and seed once.
struct GatheredCurves {
    std::vector<std::filesystem::path> runs;
    std::vector<CurveRow> rows;
};

// Reads and checks the runs (output folders of `fovrt experiment` sweeps), in the order given.
GatheredCurves GatherSweepRuns(const std::vector<std::filesystem::path>& runs);

// One comparison: a design against the anchor on one (scene, variant), with the seeds it used.
struct DesignComparison {
    RaysSavedRow saved;
    std::vector<uint32_t> seeds;
    std::vector<std::string> budgets;  // the design's points, rays ascending
    std::vector<double> rays, jod;     // per point: measured rays, seed-mean JOD over `seeds`
};
// Every design in `designs` (empty: every design but the anchor) against `anchor`, per scene and
// variant both hold. Refuses an anchor or design no run holds.
std::vector<DesignComparison> CompareDesigns(const GatheredCurves& curves, const std::string& anchor,
                                             const std::vector<std::string>& designs);

// The headline table and each design's points with the rays saved at each, as text.
std::string DesignComparisonText(const std::string& anchor, const std::vector<DesignComparison>& comparisons);

}  // namespace fovrt
