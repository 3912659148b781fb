// `fovrt rays-saved RUN...`: the rays each design saves against an anchor design at equal JOD,
// from the curves of sweeps that ran apart (app/sweep_compare.h): a design added after the anchor's
// points ran is measured against them without running them again.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/sweep_compare.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "commands.h"

namespace fovrt {

namespace {

struct RaysSavedOptions {
    std::vector<std::string> runs;
    std::string anchor = "uniform";
    std::vector<std::string> designs;  // empty: every design but the anchor
    std::vector<double> budgets;  // empty: every budget
    bool poolGaze = false;
    std::string json;  // empty: none
};

void PrintRaysSaved(const RaysSavedOptions& o) {
    std::vector<std::filesystem::path> runs(o.runs.begin(), o.runs.end());
    GatheredCurves curves = GatherSweepRuns(runs, o.poolGaze ? GazeWindows::kPooled : GazeWindows::kSame);
    KeepBudgets(curves, o.budgets);
    std::printf("%zu rows (scene, variant, design, budget, %s) from %zu runs\n", curves.rows.size(),
                curves.windows.size() > 1 ? "window, seed" : "seed", runs.size());
    const std::vector<DesignComparison> comparisons = CompareDesigns(curves, o.anchor, o.designs);
    std::printf("%s", DesignComparisonText(o.anchor, comparisons, curves.windows).c_str());
    std::printf("%s", PerWindowText(curves, o.anchor, o.designs).c_str());
    if (!o.json.empty()) {
        try {
            WriteTextAtomically(o.json, DesignComparisonJson(o.anchor, comparisons, curves).dump(2) + "\n");
        } catch (const std::filesystem::filesystem_error& e) {  // its folder cannot be made
            Fail("--json {}: {}", o.json, e.code().message());
        }
        std::printf("wrote %s\n", o.json.c_str());
    }
}

}  // namespace

void RegisterRaysSavedCommand(CLI::App& app) {
    auto o = std::make_shared<RaysSavedOptions>();
    CLI::App* cmd = app.add_subcommand(
        "rays-saved", "Rays saved at equal JOD against an anchor design, from the curves of sweeps that ran apart");
    cmd->add_option("runs", o->runs, "Output folders of `fovrt experiment` sweeps with the same configuration")
        ->required()
        ->check(CLI::ExistingDirectory);
    cmd->add_option("--anchor", o->anchor, "The design the others are measured against");
    // One design per --design, so that the run folders after it stay positionals.
    cmd->add_option("--design", o->designs, "Only this design (repeatable; default: every design but the anchor)")
        ->allow_extra_args(false);
    cmd->add_option("--budget", o->budgets,
                    "Only the points at this budget, spp (repeatable; default: every budget): runs with different "
                    "budget lists compare on those they share")
        ->allow_extra_args(false)
        ->check(CLI::PositiveNumber);
    cmd->add_flag("--pool-gaze", o->poolGaze,
                  "Gather runs that differ only in where the eye looks (gaze source, recording or trace and its start, "
                  "static direction): each gaze window with each seed is a unit of the bootstrap; then each window alone");
    cmd->add_option("--json", o->json,
                    "Also write the comparisons, every figure unrounded, to this JSON file (written whole or not at all)");
    cmd->callback([o] { PrintRaysSaved(*o); });
}

}  // namespace fovrt
