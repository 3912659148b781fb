#include "app/cluster_jobs.h"

#include <sys/stat.h>

#include <algorithm>
#include <fstream>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"

namespace fovrt {
namespace {

namespace fs = std::filesystem;

std::string Join(const std::vector<std::string>& words) {
    std::string out;
    for (const std::string& w : words) {
        if (!out.empty()) out += ' ';
        out += ShellQuote(w);
    }
    return out;
}

// The options every task of the experiment shares: the file, --quick, --seeds, the shared cache
// and output, the thread count the scheduler gives, and the user's --set overrides.
std::vector<std::string> CommonOptions(const ClusterOptions& o, bool outputToo, bool scenesToo = true) {
    std::vector<std::string> words;
    if (o.quick) words.push_back("--quick");
    if (scenesToo)
        for (const std::string& scene : o.scenes) words.insert(words.end(), {"--scene", scene});
    if (!o.seeds.empty()) words.insert(words.end(), {"--seeds", o.seeds});
    for (const std::string& s : o.sets) words.insert(words.end(), {"--set", s});
    words.insert(words.end(), {"--set", fmt::format("reference.cache_dir=\"{}\"", o.cacheDir.string())});
    if (outputToo) words.insert(words.end(), {"--set", fmt::format("output.dir=\"{}\"", o.outputDir.string())});
    words.insert(words.end(), {"--set", fmt::format("run.threads={}", o.cpusPerTask)});
    return words;
}

std::string Sbatch(const ClusterOptions& o, const fs::path& dir, const std::string& name, const std::string& tasks,
                   size_t count) {
    std::string s = "#!/bin/bash\n";
    s += fmt::format("#SBATCH --job-name=fovrt-{}\n", name);
    if (count > 1 || tasks != "merge.task") s += fmt::format("#SBATCH --array=0-{}\n", count - 1);
    if (!o.partition.empty()) s += fmt::format("#SBATCH --partition={}\n", o.partition);
    s += fmt::format("#SBATCH --time={}\n", o.timeLimit);
    s += fmt::format("#SBATCH --cpus-per-task={}\n", o.cpusPerTask);
    s += "#SBATCH --ntasks=1\n";
    if (!o.memory.empty()) s += fmt::format("#SBATCH --mem={}\n", o.memory);
    s += fmt::format("#SBATCH --output={}/logs/{}-%A_%a.out\n", dir.string(), name);
    s += "set -euo pipefail\n";
    s += fmt::format("line=$(sed -n \"$((${{SLURM_ARRAY_TASK_ID:-0}} + 1))p\" {})\n", ShellQuote((dir / tasks).string()));
    s += "[[ -n $line ]] || { echo \"no task ${SLURM_ARRAY_TASK_ID:-0}\" >&2; exit 1; }\n";
    s += "echo \"+ $line\" >&2\n";
    s += "exec bash -c \"$line\"\n";
    return s;
}

void WriteExecutable(const fs::path& path, const std::string& text) {
    WriteTextAtomically(path, text);
    ::chmod(path.c_str(), 0755);
}

std::string Lines(const std::vector<std::string>& lines) {
    std::string out;
    for (const std::string& l : lines) {
        out += l;
        out += '\n';
    }
    return out;
}

}  // namespace

std::string ShellQuote(const std::string& word) {
    if (!word.empty() && word.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789"
                                                "_-./:=,+@%") == std::string::npos)
        return word;
    std::string out(1, '\'');
    for (char c : word) {
        if (c == '\'') out.append("'\\''");
        else out.push_back(c);
    }
    out.push_back('\'');
    return out;
}

ClusterJobs MakeClusterJobs(const ClusterOptions& o, const ClusterExperiment& e) {
    if (o.shards < 1) Fail("--shards {}: at least 1", o.shards);
    if (e.scenes.empty() || e.frames < 1) Fail("the experiment has no scenes or no frames");
    ClusterJobs jobs;
    const int pairs = int(e.scenes.size()) * 2;
    const int perPair = std::clamp(o.referenceTasks > 0 ? (o.referenceTasks + pairs - 1) / pairs : 1, 1, e.frames);
    for (const std::string& scene : e.scenes)
        for (int eye = 0; eye < 2; ++eye)
            for (int chunk = 0; chunk < perPair; ++chunk) {
                const int begin = e.firstFrame + chunk * e.frames / perPair;
                const int end = e.firstFrame + (chunk + 1) * e.frames / perPair - 1;
                if (end < begin) continue;
                std::vector<std::string> words{o.fovrt, "reference", "--experiment", o.experimentFile,
                                               "--scene", scene, "--eye", std::to_string(eye),
                                               "--frames", fmt::format("{}-{}", begin, end)};
                const auto common = CommonOptions(o, false, false);  // one scene: its own --scene
                words.insert(words.end(), common.begin(), common.end());
                jobs.referenceTasks.push_back(Join(words));
            }
    for (int i = 0; i < o.shards; ++i) {
        std::vector<std::string> words{o.fovrt, "experiment", o.experimentFile, "--shard",
                                       fmt::format("{}/{}", i, o.shards)};
        const auto common = CommonOptions(o, true);
        words.insert(words.end(), common.begin(), common.end());
        jobs.experimentTasks.push_back(Join(words));
    }
    std::vector<std::string> words{o.fovrt, "experiment", o.experimentFile, "--merge"};
    const auto common = CommonOptions(o, true);
    words.insert(words.end(), common.begin(), common.end());
    jobs.mergeTask = Join(words);
    return jobs;
}

void WriteClusterJobs(const fs::path& dir, const ClusterOptions& o, const ClusterJobs& jobs) {
    fs::create_directories(dir / "logs");
    WriteTextAtomically(dir / "references.tasks", Lines(jobs.referenceTasks));
    WriteTextAtomically(dir / "experiment.tasks", Lines(jobs.experimentTasks));
    WriteTextAtomically(dir / "merge.task", jobs.mergeTask + "\n");
    WriteExecutable(dir / "references.sbatch", Sbatch(o, dir, "references", "references.tasks", jobs.referenceTasks.size()));
    WriteExecutable(dir / "experiment.sbatch", Sbatch(o, dir, "experiment", "experiment.tasks", jobs.experimentTasks.size()));
    WriteExecutable(dir / "merge.sbatch", Sbatch(o, dir, "merge", "merge.task", 1));
    const std::string d = ShellQuote(dir.string());
    WriteExecutable(dir / "submit.sh", fmt::format(
        "#!/bin/bash\n"
        "# Submits the references, the experiment shards (after every reference task succeeded) and\n"
        "# the merge (after every shard succeeded). Prints the three job ids.\n"
        "set -euo pipefail\n"
        "ref=$(sbatch --parsable {0}/references.sbatch)\n"
        "exp=$(sbatch --parsable --dependency=afterok:${{ref%%;*}} {0}/experiment.sbatch)\n"
        "merge=$(sbatch --parsable --dependency=afterok:${{exp%%;*}} {0}/merge.sbatch)\n"
        "echo \"$ref $exp $merge\"\n", d));
    WriteExecutable(dir / "run-parallel.sh", fmt::format(
        "#!/bin/bash\n"
        "# The same three steps on this machine with GNU parallel: JOBS tasks at a time (default 1).\n"
        "set -euo pipefail\n"
        "jobs=${{1:-1}}\n"
        "command -v parallel >/dev/null || {{ echo \"run-parallel.sh: GNU parallel is missing (apt-get install parallel)\" >&2; exit 1; }}\n"
        "parallel --halt now,fail=1 --jobs \"$jobs\" < {0}/references.tasks\n"
        "parallel --halt now,fail=1 --jobs \"$jobs\" < {0}/experiment.tasks\n"
        "bash -c \"$(cat {0}/merge.task)\"\n", d));
}

}  // namespace fovrt
