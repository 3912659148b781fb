// Sampling designs: the experiment axis that varies how rays are spent (docs/experiments.md,
// "Sampling designs and budget sweeps"). An experiment file may name designs, partial configs of
// the sampling side, and budgets, mean path samples per pixel:
//
//   [experiment]
//   budgets = [1, 2, 4]               # each sets foveation.ray_budget = b · width · height
//   anchor_design = "uniform"         # optional: the design rays saved are measured against
//   run_designs = ["uniform", "disc"] # optional: only these (e.g. in [experiment.quick.experiment])
//   [experiment.designs.uniform]
//   foveation.model = "uniform"
//   [experiment.designs.disc]
//   foveation = { model = "disc", spp_inside = 8, spp_outside = 1 }
//   budgets = [1, 2, 4]               # optional: this design's own (a design that cannot go below 1)
//
// Every (design, budget) is a point (a design without budgets is one point at its own sampling): the experiment's config with the design's keys merged over it
// (after [experiment.quick]), then the budget; every point runs every scene, variant and seed.
// A design may set only [foveation] keys and the eye-tracker keys of [gaze] (the rows of
// FoveationParamTable and TrackerParamTable); with budgets, not foveation.ray_budget. A key outside
// them, a name that is not one path component, a --set of a key a design sets, or a point whose
// config is invalid (an infeasible budget) is refused in one line naming the design and key.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "config/config.h"

namespace fovrt {

struct ConfigOptions;
struct ExperimentTable;

// One point of the sweep.
struct SweepPoint {
    size_t design = 0;                // index into SamplingSweep::designs
    std::optional<double> budgetSpp;  // experiment.budgets' value; none: the design's own sampling
    std::string label;                // "disc-b2": its folder under designs/ (and shards/)
    RunConfig config;                 // resolved: the experiment's, the design's keys, the budget
};

struct SamplingDesign {
    std::string name;
    std::vector<std::pair<std::string, std::string>> keys;  // dotted key -> value as TOML text
    std::vector<double> budgets;  // ascending: its own `budgets`, else experiment.budgets; empty: none
};

struct SamplingSweep {
    std::vector<SamplingDesign> designs;  // in the file's order
    std::vector<double> budgets;          // experiment.budgets, ascending (a design may have its own)
    std::optional<size_t> anchor;         // the design rays saved are measured against
    std::vector<SweepPoint> points;       // design-major, budgets ascending
    bool Active() const { return !designs.empty(); }
};

// The keys an [experiment] table may hold for the sweep.
inline constexpr const char* kSweepKeys[] = {"designs", "budgets", "anchor_design", "run_designs"};

// The sweep of `experiment` (inactive when it lists no designs). `options`, `quick`: how the
// experiment's config was resolved; `variants`: its denoisers, set on every point.
SamplingSweep LoadSamplingSweep(const ExperimentTable& experiment, const ConfigOptions& options, bool quick,
                                const std::vector<std::string>& variants);

// "disc-b1.5" for design "disc" at 1.5 spp, "disc" without budgets.
std::string SweepPointLabel(const std::string& design, std::optional<double> budgetSpp);

}  // namespace fovrt
