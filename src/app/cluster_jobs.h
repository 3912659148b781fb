// Cluster jobs for an experiment (SPEC §13, issue #15): the task lists and the scripts that run
// them on Slurm (job arrays, chained by --dependency=afterok) or on one machine with GNU parallel.
// fovrt schedules nothing itself: every task is one `fovrt` command line, the same under both
// engines, and the jobs directory holds them as plain text:
//   references.tasks   one `fovrt reference --experiment …` per (scene, eye, frame range)
//   experiment.tasks   one `fovrt experiment … --shard I/N` per shard
//   merge.task         `fovrt experiment … --merge`
//   references.sbatch, experiment.sbatch, merge.sbatch   Slurm scripts (arrays over the task lines)
//   submit.sh          sbatch all three, each after the previous succeeded; prints the job ids
//   run-parallel.sh    the same three steps on this machine with GNU parallel
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace fovrt {

struct ClusterOptions {
    std::string fovrt;                   // the executable the tasks run (absolute)
    std::string experimentFile;          // absolute
    bool quick = false;
    std::string seeds;                   // --seeds as given ("" = the file's)
    std::vector<std::string> scenes;     // --scene as given (empty = the file's)
    std::vector<std::string> sets;       // --set overrides, passed to every task
    int shards = 4;                      // experiment shards
    int referenceTasks = 0;              // 0: one per (scene, eye)
    std::string partition;               // "" = the cluster's default
    std::string timeLimit = "04:00:00";  // per task, sbatch --time
    int cpusPerTask = 2;
    std::string memory;                  // sbatch --mem ("" = the partition's default)
    std::filesystem::path cacheDir;      // shared reference cache (absolute)
    std::filesystem::path outputDir;     // experiment output (absolute)
};

// What the experiment needs rendered: its scenes and frames (from LoadExperiment).
struct ClusterExperiment {
    std::vector<std::string> scenes;
    int firstFrame = 0;
    int frames = 0;
};

struct ClusterJobs {
    std::vector<std::string> referenceTasks;
    std::vector<std::string> experimentTasks;
    std::string mergeTask;
};

// The task command lines (shell-quoted). Reference tasks split each (scene, eye)'s frames into
// ranges so that there are about `referenceTasks` of them.
ClusterJobs MakeClusterJobs(const ClusterOptions& options, const ClusterExperiment& experiment);
// Writes the jobs directory (see above); the scripts are executable.
void WriteClusterJobs(const std::filesystem::path& dir, const ClusterOptions& options, const ClusterJobs& jobs);

// POSIX shell quoting of one word.
std::string ShellQuote(const std::string& word);

}  // namespace fovrt
