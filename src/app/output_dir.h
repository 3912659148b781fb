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
// Earlier outputs move aside, never mix in (app/earlier_outputs.h): a command records what it
// wrote in the folder's ledger, and the next one moves exactly that into a previous-run-<start>/
// folder of its own, leaving every file fovrt did not write where it is.
//
// A command that fails leaves no trace of its own: when this object created the folder and holds
// its folder lock, the folder goes whole (nobody else can have written into it); in a folder that
// existed, under its folder lock, what the command added once the earlier outputs were moved
// aside (a frames.jsonl, half a frame's images) goes; otherwise only the directories it created,
// and only while empty. Keep() (success, or an interrupt whose outputs the command reports) keeps
// everything and lists it in the ledger.
//
// The filesystem root and the user's home are refused as such a folder: the rules above would
// act on the user's own files there.
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
    // Creates `path` and checks that a file can be written in it; fovrt::Error naming `key`
    // and the path otherwise (the filesystem root and $HOME are refused before anything is made).
    OutputDir(std::filesystem::path path, std::string key);
    ~OutputDir();
    OutputDir(const OutputDir&) = delete;
    OutputDir& operator=(const OutputDir&) = delete;

    const std::filesystem::path& Path() const { return path_; }
    // Takes the lock `lockName` (kFolderLock, or a shard's own) or throws fovrt::Error naming the
    // holder. Held until destruction.
    void Lock(const std::string& lockName = kFolderLock);
    // Moves what the previous fovrt run, experiment or merge wrote here (what its ledger lists;
    // with `sceneDirs`, also the per-scene folders an experiment's manifest names) into a new
    // previous-run-<its start>[-partial]/, so no stale file sits beside this command's outputs and
    // no earlier run is lost. Files fovrt did not write are left alone. Says what it moved on
    // stderr, then starts this command's ledger.
    void MoveAsideEarlierOutputs(bool sceneDirs);
    // The command succeeded (or was interrupted and says what it left): keep what it wrote, and
    // list it in the ledger.
    void Keep();

private:
    void RemoveCreated();
    void RemoveAdded();

    std::filesystem::path path_;
    std::string key_;
    std::vector<std::filesystem::path> created_;  // deepest first
    std::filesystem::path lockPath_;
    int lockFd_ = -1;
    bool folderLocked_ = false;
    // Once the earlier outputs were moved aside: when, and what the folder held then (FolderContents);
    // everything else there is this command's (Keep lists it, RemoveAdded removes it).
    std::string started_;
    std::optional<std::set<std::string>> before_;
};

}  // namespace fovrt
