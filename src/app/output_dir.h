// OutputDir: a directory a command writes into, named by its config key (output.dir,
// reference.cache_dir). Created (with its parents) and checked writable before any rendering, so a
// bad path is one line naming the key, the path and the system's reason, not a filesystem
// exception or a failure after minutes of work.
//
// One writer per folder: Lock() takes an advisory lock (flock) on a lock file in the folder for
// the object's lifetime and writes the holder (pid, host, command line, start time) into it; a
// second command locking the same file refuses in one line naming that holder. `run`, a whole or
// merged `experiment` lock ".fovrt.lock"; a shard locks its own file, so the shards of one
// experiment still run side by side (they write disjoint parts).
//
// A command that fails leaves no trace of its own: when this object created the folder and holds
// its folder lock, the folder goes whole (nobody else can have written into it); in a folder that
// existed, under its folder lock, what the command added at its top once the earlier outputs were
// moved aside (a frames.jsonl, half a frame's images) goes; otherwise only the directories it
// created, and only while empty. Keep() (success, or an interrupt whose outputs the command
// reports) keeps everything.
#pragma once

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace fovrt {

class OutputDir {
public:
    // The lock file of a whole folder (`run`, `experiment`, `experiment --merge`).
    static constexpr const char* kFolderLock = ".fovrt.lock";
    // Where MoveAsideEarlierOutputs puts an earlier run's outputs (one generation kept).
    static constexpr const char* kPreviousRun = "previous-run";

    // Creates `path` and checks that a file can be written in it; fovrt::Error naming `key`
    // and the path otherwise.
    OutputDir(std::filesystem::path path, std::string key);
    ~OutputDir();
    OutputDir(const OutputDir&) = delete;
    OutputDir& operator=(const OutputDir&) = delete;

    const std::filesystem::path& Path() const { return path_; }
    // Takes the lock `lockName` (kFolderLock, or a shard's own) or throws fovrt::Error naming the
    // holder. Held until destruction.
    void Lock(const std::string& lockName = kFolderLock);
    // Moves what an earlier fovrt run or experiment wrote here (manifest, frames.jsonl, frames and
    // CSVs, summary, report; with `sceneDirs`, the per-scene folders its manifest names) into
    // kPreviousRun/, replacing the generation there, so no stale file sits beside this run's
    // outputs. Files fovrt does not write are left alone. Says what it moved on stderr.
    void MoveAsideEarlierOutputs(bool sceneDirs);
    // The command succeeded (or was interrupted and says what it left): keep what it wrote.
    void Keep() {
        created_.clear();
        kept_.reset();
    }

private:
    void RemoveCreated();
    void RemoveAdded();

    std::filesystem::path path_;
    std::string key_;
    std::vector<std::filesystem::path> created_;  // deepest first
    std::filesystem::path lockPath_;
    int lockFd_ = -1;
    bool folderLocked_ = false;
    // A folder that existed, under the folder lock: what was at its top once the earlier outputs
    // were moved aside; everything else there is this command's (RemoveAdded).
    std::optional<std::set<std::string>> kept_;
};

}  // namespace fovrt
