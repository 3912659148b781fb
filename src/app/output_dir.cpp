#include "app/output_dir.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"

namespace fovrt {

namespace fs = std::filesystem;

namespace {

// What an earlier run or experiment writes at the top of its folder (cmd_run.cpp,
// experiment.cpp); shards/ is not among them (a merge reads it).
const char* const kEarlierOutputs[] = {"manifest.json", "frames.jsonl", "inputs",      "noisy",
                                       "denoised",      "summary.json", "report.html", "jod.csv"};
constexpr const char* kCsvPrefix = "frames-";  // frames-<scene>.csv

// The holder written into the lock file: "pid 12 on host, started 2026-01-01 10:00:00 UTC: fovrt run ...".
std::string HolderText() {
    char host[256] = "host";
    ::gethostname(host, sizeof host - 1);
    std::string command;
    std::ifstream cmdline("/proc/self/cmdline", std::ios::binary);
    for (std::string arg; std::getline(cmdline, arg, '\0');) command += (command.empty() ? "" : " ") + arg;
    if (command.size() > 300) command = command.substr(0, 300) + " ...";
    return fmt::format("pid {} on {}, started {:%Y-%m-%d %H:%M:%S} UTC: {}", ::getpid(), host,
                       fmt::gmtime(std::chrono::system_clock::to_time_t(std::chrono::system_clock::now())),
                       command);
}

}  // namespace

OutputDir::OutputDir(fs::path path, std::string key) : path_(std::move(path)), key_(std::move(key)) {
    if (path_.empty()) Fail("config key '{}': must not be empty", key_);
    // Remember which of the path's directories do not exist yet: those are the run's to remove.
    std::error_code ec;
    for (fs::path p = path_; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        created_.push_back(p);
        if (p == p.parent_path()) break;
    }
    auto fail = [&](const std::string& why) {
        Fail("config key '{}': cannot write to '{}': {}", key_, path_.string(), why);
    };
    // mkdir one level at a time so the reason is the system's own (create_directories reports
    // "Success" where /proc refuses a mkdir).
    for (auto it = created_.rbegin(); it != created_.rend(); ++it) {
        if (::mkdir(it->c_str(), 0777) == 0 || errno == EEXIST) continue;
        const std::string why = fmt::format("cannot create '{}': {}", it->string(), std::strerror(errno));
        RemoveCreated();  // the part that did get created
        fail(why);
    }
    if (!fs::is_directory(path_, ec)) {
        created_.clear();
        fail("not a directory");
    }
    const fs::path probe = path_ / fmt::format(".fovrt-write-test-{}", ::getpid());
    std::FILE* file = std::fopen(probe.c_str(), "wb");
    if (!file) {
        const std::string why = std::strerror(errno);
        RemoveCreated();  // a constructor that throws runs no destructor
        fail(why);
    }
    std::fclose(file);
    fs::remove(probe, ec);
}

OutputDir::~OutputDir() {
    RemoveCreated();
    RemoveAdded();
    if (lockFd_ >= 0) ::close(lockFd_);  // releases the lock
}

void OutputDir::Lock(const std::string& lockName) {
    const fs::path lockPath = path_ / lockName;
    const int fd = ::open(lockPath.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) Fail("config key '{}': cannot open lock file '{}': {}", key_, lockPath.string(), std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        const int error = errno;
        std::string holder;
        char buffer[512];
        const ssize_t n = ::pread(fd, buffer, sizeof buffer - 1, 0);
        if (n > 0) holder.assign(buffer, size_t(n));
        while (!holder.empty() && (holder.back() == '\n' || holder.back() == '\0')) holder.pop_back();
        ::close(fd);
        if (error != EWOULDBLOCK)
            Fail("config key '{}': cannot lock '{}': {}", key_, lockPath.string(), std::strerror(error));
        Fail("config key '{}': '{}' is in use by another fovrt ({}; lock {})", key_, path_.string(),
             holder.empty() ? "holder unknown" : holder, lockPath.string());
    }
    // The holder's description is informational: a failed write (a full disk) does not stop the run.
    const std::string holder = HolderText() + "\n";
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, holder.data(), holder.size(), 0) < 0) {
    }
    lockFd_ = fd;
    lockPath_ = lockPath;
    folderLocked_ = lockName == kFolderLock;
}

void OutputDir::MoveAsideEarlierOutputs(bool sceneDirs) {
    std::error_code ec;
    std::vector<std::string> names(std::begin(kEarlierOutputs), std::end(kEarlierOutputs));
    for (const auto& entry : fs::directory_iterator(path_, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind(kCsvPrefix, 0) == 0 && entry.path().extension() == ".csv") names.push_back(name);
    }
    if (sceneDirs && fs::exists(path_ / "manifest.json")) {
        try {
            std::ifstream in(path_ / "manifest.json");
            const nlohmann::json manifest = nlohmann::json::parse(in);
            if (manifest.value("command", "") == "experiment")
                for (const auto& scene : manifest.at("scenes")) {
                    const std::string label = scene.at("scene");
                    if (!label.empty() && label.find('/') == std::string::npos && label[0] != '.') names.push_back(label);
                }
        } catch (const std::exception&) {
            // Not an experiment's manifest: its scene folders are unknown, leave them.
        }
    }
    std::vector<std::string> moved;
    const fs::path previous = path_ / kPreviousRun;
    for (const std::string& name : names) {
        if (!fs::exists(path_ / name, ec)) continue;
        if (moved.empty()) {
            fs::remove_all(previous);  // only ever holds what an earlier call moved there
            fs::create_directory(previous);
        }
        fs::rename(path_ / name, previous / name);
        moved.push_back(fs::is_directory(previous / name, ec) ? name + "/" : name);
    }
    if (!moved.empty())
        std::fprintf(stderr, "fovrt: moved the earlier outputs in %s (%s) to %s/\n", path_.c_str(),
                     fmt::format("{}", fmt::join(moved, ", ")).c_str(), previous.c_str());
    if (folderLocked_ && created_.empty()) {  // a new folder goes whole on failure (RemoveCreated)
        kept_.emplace();
        for (const auto& entry : fs::directory_iterator(path_, ec)) kept_->insert(entry.path().filename().string());
    }
}

void OutputDir::RemoveAdded() {
    if (!kept_) return;
    std::error_code ec;
    std::vector<fs::path> added;
    for (const auto& entry : fs::directory_iterator(path_, ec))
        if (!kept_->count(entry.path().filename().string())) added.push_back(entry.path());
    for (const fs::path& p : added) fs::remove_all(p, ec);
    kept_.reset();
}

void OutputDir::RemoveCreated() {
    if (created_.empty()) return;
    std::error_code ec;
    if (folderLocked_) {
        // A new folder under this command's lock: everything in it is the command's.
        fs::remove_all(path_, ec);
    } else {
        // Others may write here (a shard's neighbours): only this command's lock file and empty
        // subdirectories, deepest first (files, and the directories holding them, stay).
        if (lockFd_ >= 0) fs::remove(lockPath_, ec);
        std::vector<fs::path> subdirs;
        for (fs::recursive_directory_iterator it(path_, ec), end; !ec && it != end; it.increment(ec))
            if (it->is_directory(ec)) subdirs.push_back(it->path());
        for (auto it = subdirs.rbegin(); it != subdirs.rend(); ++it)
            if (fs::is_empty(*it, ec)) fs::remove(*it, ec);
    }
    for (const fs::path& p : created_) {
        if (!fs::exists(p, ec)) continue;  // never got created
        if (!fs::is_directory(p, ec) || !fs::is_empty(p, ec)) break;
        fs::remove(p, ec);
    }
    created_.clear();
}

}  // namespace fovrt
