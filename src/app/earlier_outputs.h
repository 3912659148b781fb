// Earlier outputs: which files in an output folder the previous fovrt command wrote, and moving
// exactly those into a folder of their own, so a rerun never mixes its outputs with another's and
// never moves (or loses) a file fovrt did not write.
//
// Every `run`, whole `experiment` and merge keeps a ledger, <output.dir>/.fovrt-outputs.json: when
// it starts, its start time and what the folder held then (not its own); when it ends, whether it
// succeeded or was interrupted, every file and directory it added. The next command moves the
// files the ledger lists into previous-run-<start time>/ (UTC), or, where the command was killed
// before it could list them, every file the folder did not hold when it started. A run that left
// no manifest goes to previous-run-<start time>-partial/. Earlier generations stay until the user
// removes them. A folder without a ledger (a fovrt that kept none) falls back to the names such a
// command writes at the top of the folder.
#pragma once

#include <filesystem>
#include <optional>
#include <set>
#include <string>

namespace fovrt {

constexpr const char* kOutputsLedger = ".fovrt-outputs.json";
constexpr const char* kPreviousRunPrefix = "previous-run-";

// The paths (relative, '/'-separated) of every file and directory under `dir`, leaving out what no
// single command owns: fovrt's own lock and ledger files (".fovrt*"), earlier generations
// ("previous-run*") and shards/ (written by shards side by side, read by a merge).
std::set<std::string> FolderContents(const std::filesystem::path& dir);

// What the previous command in a folder wrote.
struct EarlierRun {
    std::set<std::string> paths;  // relative; files move one by one, its directories go once empty
    std::string started;          // its start, "20261128T045408Z"
    bool ledger = false;          // a ledger was found (it moves with the run)
};

// From the folder's ledger, or the names an earlier fovrt writes where there is none.
EarlierRun FindEarlierRun(const std::filesystem::path& dir);
// Adds the folder `name` (an experiment's scene folder) and everything under it.
void AddFolder(const std::filesystem::path& dir, const std::string& name, EarlierRun& run);

// Moves `run`'s files into a new previous-run-<start>[-partial]/ in `dir` (complete: its
// manifest.json is among them) and removes its directories left empty. Says what moved on stderr;
// fovrt::Error naming the file and the reason when something cannot be moved.
// A run that wrote nothing only has its ledger removed.
void MoveAside(const std::filesystem::path& dir, const EarlierRun& run);

// The ledger: at the start (`added` empty: the command has not ended) and at the end. Returns
// false when it could not be written.
bool WriteLedger(const std::filesystem::path& dir, const std::string& started, const std::set<std::string>& before,
                 const std::optional<std::set<std::string>>& added);

// Now, as a ledger's start time.
std::string StartTimeNow();

}  // namespace fovrt
