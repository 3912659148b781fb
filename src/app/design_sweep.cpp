#include "app/design_sweep.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include <fmt/format.h>

#include "app/experiment_pass.h"
#include "app/experiment_run.h"
#include "app/experiment_shards.h"
#include "app/sweep_outputs.h"
#include "core/cpu_time.h"

namespace fovrt {
namespace {

namespace fs = std::filesystem;

// The experiment a point runs: the sweep's with the point's config and no sweep of its own.
ExperimentSpec PointSpec(const ExperimentSpec& spec, const SweepPoint& point) {
    ExperimentSpec p = spec;
    p.config = point.config;
    p.sweep = {};
    p.scoredFoveation = spec.config.foveation;  // one fovea for every design
    return p;
}

// What the sweep keeps of a point's part once its own outputs are written.
SweepPointResult Keep(size_t index, const ExperimentPart& part, Results results) {
    SweepPointResult r;
    r.point = index;
    std::vector<const SceneRecord*> scenes;
    for (const SceneRecord& s : part.scenes) scenes.push_back(&s);
    std::ranges::sort(scenes, {}, &SceneRecord::index);
    for (const SceneRecord* s : scenes) {
        r.scenes.push_back(s->label);
        auto& spp = r.tracedSpp[s->label];
        for (size_t i = 0; i < spp.size(); ++i) spp[i] = TracedSamples::SamplesPerPixel(*s, i);
        r.guideRays[s->label] = TracedSamples::GuideRaysPerPixel(*s, 0);
    }
    r.results = std::move(results);
    r.vdp = part.vdp;
    return r;
}

void Announce(const ExperimentSpec& spec, size_t index, const char* what) {
    const SweepPoint& point = spec.sweep.points[index];
    std::fprintf(stderr, "fovrt experiment: %s point %zu of %zu: design %s%s\n", what, index + 1,
                 spec.sweep.points.size(), spec.sweep.designs[point.design].name.c_str(),
                 point.budgetSpp ? fmt::format(" at {:g} spp", *point.budgetSpp).c_str() : "");
}

}  // namespace

Results RunSweep(const ExperimentSpec& spec, OutputDir& out) {
    const auto start = std::chrono::steady_clock::now();
    const fs::path outDir = out.Path();
    const SamplingSweep& sweep = spec.sweep;
    const std::vector<uint32_t> seeds = spec.seeds.empty() ? std::vector<uint32_t>{spec.config.run.seed} : spec.seeds;
    const std::vector<RunUnit> perPoint = ExperimentUnits(spec.scenes.size(), seeds.size(), spec.variants.size());
    auto pointDir = [&](size_t p) { return outDir / "designs" / sweep.points[p].label; };
    auto shardsDir = [&](size_t p) { return outDir / "shards" / sweep.points[p].label; };

    if (spec.shard.Sharded()) {
        // One block of the runs of all points in order; every point writes its part (possibly
        // empty), so each point's merge finds all N.
        const size_t total = perPoint.size() * sweep.points.size();
        const auto [begin, end] = ShardBlock(total, spec.shard);
        for (size_t p = 0; p < sweep.points.size(); ++p) {
            std::vector<RunUnit> units;
            for (size_t u = 0; u < perPoint.size(); ++u) {
                const size_t global = p * perPoint.size() + u;
                if (global >= begin && global < end) units.push_back(perPoint[u]);
            }
            const ExperimentSpec point = PointSpec(spec, sweep.points[p]);
            if (!units.empty()) Announce(spec, p, "computing");
            ExperimentPart part = units.empty() ? ExperimentPart{} : ComputeRuns(point, units, pointDir(p));
            WriteShardPart(shardsDir(p), spec.shard, ExperimentFingerprint(point), part);
        }
        std::fprintf(stderr, "fovrt experiment: %s (%zu of %zu runs over %zu points) done in %.1f s, %.1f s CPU\n",
                     spec.shard.Name().c_str(), end - begin, total, sweep.points.size(), MsSince(start) / 1000.0,
                     CpuSeconds());
        return {};
    }

    out.MoveAsideEarlierOutputs(!spec.merge);
    std::vector<SweepPointResult> results;
    for (size_t p = 0; p < sweep.points.size(); ++p) {
        const ExperimentSpec point = PointSpec(spec, sweep.points[p]);
        Announce(spec, p, spec.merge ? "merging" : "computing");
        ExperimentPart part = spec.merge
                                  ? MergeShardParts(shardsDir(p), ExperimentFingerprint(point), RerunCommand(spec))
                                  : ComputeRuns(point, perPoint, pointDir(p));
        fs::create_directories(pointDir(p));
        Results pointResults =
            WriteExperimentOutputs(point, part, pointDir(p), start, ExperimentOutputs::kFilesOnly);
        results.push_back(Keep(p, part, std::move(pointResults)));
    }
    WriteSweepOutputs(spec, results, outDir, start);
    return results.front().results;  // the first point's: every point's are in its own folder
}

}  // namespace fovrt
