// Runs an experiment's sampling-design sweep (app/sampling_designs.h): every point is the whole
// experiment with that point's sampling, computed, sharded and merged exactly as a single
// experiment is, its outputs in <output.dir>/designs/<point>/ (its shard parts in
// <output.dir>/shards/<point>/); the references are the same for every point (the sampling does
// not change them), so the cache renders each once. Then the sweep's own outputs
// (app/sweep_outputs.h): rate–quality curves, rays saved against the anchor design, the report.
#pragma once

#include "app/experiment.h"
#include "app/output_dir.h"

namespace fovrt {

// `out`: the experiment's locked output folder. `--shard I/N` computes a contiguous block of the
// runs of every point in order (design, budget, scene, seed, eye, variant); `--merge` merges
// every point's parts, then writes the sweep's outputs. Returns the first point's results.
Results RunSweep(const ExperimentSpec& spec, OutputDir& out);

}  // namespace fovrt
