// `fovrt cluster FILE [--quick] [--seeds …] [--set …] --shards N …`: writes the jobs that run an
// experiment on a Slurm cluster (job arrays chained by afterok) or on one machine with GNU parallel
// (cluster_jobs.h), and with --submit submits them.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "app/cluster_jobs.h"
#include "app/commands.h"
#include "config/config_cli.h"
#include "app/experiment.h"
#include "core/error.h"

namespace fovrt {
namespace {

namespace fs = std::filesystem;

std::string SelfPath() {
    std::error_code error;
    const fs::path self = fs::read_symlink("/proc/self/exe", error);
    return error ? "fovrt" : self.string();
}

}  // namespace

void RegisterClusterCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "cluster", "Write (and --submit) the Slurm job arrays, or GNU parallel script, that run an experiment: "
                   "references, experiment shards, merge");
    auto config = std::make_shared<ConfigOptions>();
    auto args = std::make_shared<ExperimentArgs>();
    auto o = std::make_shared<ClusterOptions>();
    auto jobsDir = std::make_shared<std::string>("jobs");
    auto submit = std::make_shared<bool>(false);
    cmd->add_option("file", config->configPath, "Experiment file (presets/*.toml)")->required();
    cmd->add_flag("--quick", args->quick, "The file's [experiment.quick] overrides");
    cmd->add_option("--seeds", args->seeds, "Run seeds, as `experiment --seeds`");
    cmd->add_option("--scene", args->scenes, "Only these scenes, as `experiment --scene` (repeatable)");
    cmd->add_option("--set", config->sets, "Override a config key in every task: section.key=value");
    cmd->add_option("--shards", o->shards, "Experiment shards (the second job array's size)")->check(CLI::PositiveNumber);
    cmd->add_option("--reference-tasks", o->referenceTasks,
                    "About this many reference tasks (frame ranges per scene and eye; 0: one per scene and eye)");
    cmd->add_option("--partition", o->partition, "Slurm partition (default: the cluster's)");
    cmd->add_option("--time", o->timeLimit, "Time limit per task (sbatch --time)");
    cmd->add_option("--cpus-per-task", o->cpusPerTask, "CPUs per task; also each task's run.threads")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--mem", o->memory, "Memory per task (sbatch --mem)");
    cmd->add_option("--jobs-dir", *jobsDir, "Where the task lists and scripts go");
    cmd->add_flag("--submit", *submit, "Run the jobs directory's submit.sh (sbatch) after writing it");
    cmd->callback([config, args, o, jobsDir, submit] {
        // The experiment as the tasks will see it: checks the file, the scenes and the seeds now.
        ConfigOptions resolved = *config;
        const ExperimentSpec spec = LoadExperiment(resolved, *args);
        if (spec.replay) Fail("fovrt cluster: --replay experiments are not sharded");
        ClusterOptions options = *o;
        options.fovrt = SelfPath();
        options.experimentFile = fs::absolute(config->configPath).string();
        options.quick = args->quick;
        options.seeds = args->seeds;
        options.scenes = args->scenes;
        options.sets.clear();
        for (const std::string& s : config->sets)
            if (s.rfind("output.dir=", 0) != 0 && s.rfind("reference.cache_dir=", 0) != 0) options.sets.push_back(s);
        options.cacheDir = fs::absolute(spec.config.reference.cacheDir);
        options.outputDir = fs::absolute(spec.config.output.dir);
        const ClusterJobs jobs =
            MakeClusterJobs(options, {spec.scenes, spec.config.run.firstFrame, spec.config.run.frames});
        const fs::path dir = fs::absolute(*jobsDir);
        WriteClusterJobs(dir, options, jobs);
        std::fprintf(stderr,
                     "fovrt cluster: %zu reference tasks, %zu experiment shards, 1 merge -> %s (submit.sh for Slurm, "
                     "run-parallel.sh for GNU parallel)\n",
                     jobs.referenceTasks.size(), jobs.experimentTasks.size(), dir.string().c_str());
        if (*submit) {
            const std::string command = ShellQuote((dir / "submit.sh").string());
            const int status = std::system(command.c_str());
            if (status != 0) Fail("fovrt cluster: {} failed (exit status {}): is Slurm's sbatch available?", command, status);
        }
    });
}

}  // namespace fovrt
