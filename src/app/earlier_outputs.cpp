#include "app/earlier_outputs.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <vector>

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"

namespace fovrt {

namespace fs = std::filesystem;

namespace {

// Without a ledger: what an earlier run or experiment writes at the top of its folder
// (cmd_run.cpp, experiment.cpp), and the prefixes of its per-scene CSVs.
const char* const kEarlierOutputs[] = {"manifest.json", "frames.jsonl", "inputs",      "noisy",
                                       "denoised",      "summary.json", "report.html", "jod.csv"};
const char* const kCsvPrefixes[] = {"frames-", "gaze-"};  // frames-<scene>.csv, gaze-<scene>.csv

constexpr const char* kStartFormat = "{:%Y%m%dT%H%M%SZ}";

bool OwnedByNoCommand(const std::string& topName) {
    return topName.rfind(".fovrt", 0) == 0 || topName.rfind("previous-run", 0) == 0 || topName == "shards";
}

void AddTree(const fs::path& dir, const std::string& relative, std::set<std::string>& paths) {
    std::error_code ec;
    const fs::path path = dir / relative;
    if (!fs::exists(fs::symlink_status(path, ec))) return;
    paths.insert(relative);
    if (!fs::is_directory(fs::symlink_status(path, ec))) return;
    for (const auto& entry : fs::directory_iterator(path, ec))
        AddTree(dir, relative + "/" + entry.path().filename().string(), paths);
}

std::string StartTimeOf(const fs::file_time_type& time) {
    const auto system = std::chrono::time_point_cast<std::chrono::system_clock::duration>(
        std::chrono::system_clock::now() + (time - fs::file_time_type::clock::now()));
    return fmt::format(kStartFormat, fmt::gmtime(std::chrono::system_clock::to_time_t(system)));
}

// The names a fovrt without a ledger wrote; its start: its manifest's or frames list's time.
EarlierRun FindByName(const fs::path& dir) {
    EarlierRun run;
    std::error_code ec;
    std::vector<std::string> names(std::begin(kEarlierOutputs), std::end(kEarlierOutputs));
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        for (const char* prefix : kCsvPrefixes)
            if (name.rfind(prefix, 0) == 0 && entry.path().extension() == ".csv") names.push_back(name);
    }
    for (const std::string& name : names) AddTree(dir, name, run.paths);
    for (const char* record : {"manifest.json", "frames.jsonl"}) {
        const fs::file_time_type time = fs::last_write_time(dir / record, ec);
        if (!ec) {
            run.started = StartTimeOf(time);
            break;
        }
    }
    if (run.started.empty()) run.started = StartTimeNow();
    return run;
}

std::set<std::string> StringSet(const nlohmann::json& list) {
    std::set<std::string> set;
    for (const auto& item : list) set.insert(item.get<std::string>());
    return set;
}

// Moves `from` to `to`, creating `to`'s parents; fovrt::Error naming both and the reason when it
// cannot (a stale file left beside the new outputs is what moving aside prevents).
void MoveFile(const fs::path& from, const fs::path& to) {
    std::error_code ec;
    fs::create_directories(to.parent_path(), ec);
    if (!ec) fs::rename(from, to, ec);
    if (ec) Fail("cannot move the earlier output '{}' to '{}': {}", from.string(), to.string(), ec.message());
}

}  // namespace

std::string StartTimeNow() {
    return fmt::format(kStartFormat, fmt::gmtime(std::chrono::system_clock::to_time_t(std::chrono::system_clock::now())));
}

std::set<std::string> FolderContents(const fs::path& dir) {
    std::set<std::string> paths;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (!OwnedByNoCommand(name)) AddTree(dir, name, paths);
    }
    return paths;
}

EarlierRun FindEarlierRun(const fs::path& dir) {
    std::error_code ec;
    const fs::path ledgerPath = dir / kOutputsLedger;
    if (!fs::exists(ledgerPath, ec)) return FindByName(dir);
    EarlierRun run;
    run.ledger = true;
    try {
        std::ifstream in(ledgerPath);
        const nlohmann::json ledger = nlohmann::json::parse(in);
        run.started = ledger.at("started").get<std::string>();
        if (ledger.contains("added")) {
            run.paths = StringSet(ledger.at("added"));
        } else {
            // Killed before it could list them: everything the folder did not hold when it started.
            const std::set<std::string> before = StringSet(ledger.at("before"));
            for (const std::string& path : FolderContents(dir))
                if (!before.count(path)) run.paths.insert(path);
        }
    } catch (const std::exception&) {
        // Unreadable (cut short by a full disk): the names an earlier command writes.
        run = FindByName(dir);
        run.ledger = true;
    }
    // It names a folder: only what StartTimeNow writes.
    const bool plain = std::all_of(run.started.begin(), run.started.end(),
                                   [](unsigned char c) { return std::isalnum(c) || c == '-'; });
    if (run.started.empty() || !plain) run.started = StartTimeNow();
    return run;
}

void AddFolder(const fs::path& dir, const std::string& name, EarlierRun& run) { AddTree(dir, name, run.paths); }

void MoveAside(const fs::path& dir, const EarlierRun& run) {
    std::error_code ec;
    // Its directories, deepest first, once nothing is left in them (a user's file keeps its folder).
    auto removeEmptyDirectories = [&] {
        for (auto it = run.paths.rbegin(); it != run.paths.rend(); ++it)
            if (fs::is_directory(fs::symlink_status(dir / *it, ec)) && fs::is_empty(dir / *it, ec))
                fs::remove(dir / *it, ec);
    };
    std::vector<std::string> files;
    for (const std::string& path : run.paths)
        if (fs::exists(fs::symlink_status(dir / path, ec)) && !fs::is_directory(fs::symlink_status(dir / path, ec)))
            files.push_back(path);
    if (files.empty()) {  // a run that left nothing (it failed): nothing to keep
        removeEmptyDirectories();
        if (run.ledger) fs::remove(dir / kOutputsLedger, ec);
        return;
    }
    // A run is complete when it wrote its manifest (the last thing `run` and `experiment` write).
    const bool complete = run.paths.count("manifest.json") > 0;
    fs::path previous;
    for (int n = 1;; ++n) {
        previous = dir / fmt::format("{}{}{}{}", kPreviousRunPrefix, run.started, n > 1 ? fmt::format("-{}", n) : "",
                                     complete ? "" : "-partial");
        if (fs::create_directory(previous, ec)) break;  // false without an error: taken already
        if (ec) Fail("cannot move the earlier outputs aside: cannot create '{}': {}", previous.string(), ec.message());
    }
    std::set<std::string> moved;  // top-level names, as the message lists them
    for (const std::string& file : files) {
        MoveFile(dir / file, previous / file);
        const size_t slash = file.find('/');
        moved.insert(slash == std::string::npos ? file : file.substr(0, slash + 1));
    }
    if (run.ledger) MoveFile(dir / kOutputsLedger, previous / kOutputsLedger);
    removeEmptyDirectories();
    std::fprintf(stderr, "fovrt: moved the earlier outputs in %s (%s) to %s/%s\n", dir.c_str(),
                 fmt::format("{}", fmt::join(moved, ", ")).c_str(), previous.c_str(),
                 complete ? "" : " (a partial run: it left no manifest)");
}

bool WriteLedger(const fs::path& dir, const std::string& started, const std::set<std::string>& before,
                 const std::optional<std::set<std::string>>& added) {
    nlohmann::json ledger = {{"started", started}, {"before", before}};
    if (added) ledger["added"] = *added;
    const fs::path path = dir / kOutputsLedger;
    const fs::path temp = dir / fmt::format("{}.tmp", kOutputsLedger);
    {
        std::ofstream out(temp, std::ios::binary);
        out << ledger.dump(1) << '\n';
        out.flush();
        if (!out) {
            out.close();
            std::error_code ec;
            fs::remove(temp, ec);
            return false;
        }
    }
    std::error_code ec;
    fs::rename(temp, path, ec);
    return !ec;
}

}  // namespace fovrt
