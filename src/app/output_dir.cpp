#include "app/output_dir.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/earlier_outputs.h"
#include "core/error.h"

namespace fovrt {

namespace fs = std::filesystem;

namespace {

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

// The filesystem root and the user's home hold the user's own files, which the earlier-outputs
// rules (moving aside, removal after a failure) must never act on: refused, before anything is made.
void RefuseSharedFolder(const fs::path& path, const std::string& key) {
    std::error_code ec;
    const fs::path resolved = fs::weakly_canonical(fs::absolute(path, ec), ec);
    if (ec) return;  // the constructor's own checks give the reason
    if (resolved == resolved.root_path())
        Fail("config key '{}': '{}' is the filesystem root; name a folder of its own for the outputs", key,
             path.string());
    const char* home = std::getenv("HOME");
    if (home && *home && fs::equivalent(resolved, fs::path(home), ec))
        Fail("config key '{}': '{}' is the home folder ($HOME); name a folder of its own for the outputs", key,
             path.string());
}

}  // namespace

OutputDir::OutputDir(fs::path path, std::string key) : path_(std::move(path)), key_(std::move(key)) {
    if (path_.empty()) Fail("config key '{}': must not be empty", key_);
    RefuseSharedFolder(path_, key_);
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
    EarlierRun earlier = FindEarlierRun(path_);
    if (sceneDirs && fs::exists(path_ / "manifest.json")) {
        try {
            std::ifstream in(path_ / "manifest.json");
            const nlohmann::json manifest = nlohmann::json::parse(in);
            if (manifest.value("command", "") == "experiment")
                for (const auto& scene : manifest.at("scenes")) {
                    const std::string label = scene.at("scene");
                    if (!label.empty() && label.find('/') == std::string::npos && label[0] != '.')
                        AddFolder(path_, label, earlier);
                }
        } catch (const std::exception&) {
            // Not an experiment's manifest: its scene folders are unknown, leave them.
        }
    }
    MoveAside(path_, earlier);
    // This command's ledger: what the folder holds now is not its own.
    started_ = StartTimeNow();
    before_ = FolderContents(path_);
    if (!WriteLedger(path_, started_, *before_, std::nullopt))
        Fail("config key '{}': cannot write '{}': {}", key_, (path_ / kOutputsLedger).string(), std::strerror(errno));
}

void OutputDir::Keep() {
    created_.clear();
    if (!before_) return;
    // What it added, for the next command to move aside. Should the disk refuse even this, the
    // start's ledger stays and the next command takes everything added since (the killed-run rule).
    std::set<std::string> added;
    for (const std::string& path : FolderContents(path_))
        if (!before_->count(path)) added.insert(path);
    WriteLedger(path_, started_, *before_, added);
    before_.reset();
}

void OutputDir::RemoveAdded() {
    if (!before_) return;
    std::error_code ec;
    if (fs::exists(path_, ec)) {
        // The topmost of the paths it added (a directory goes whole), then a ledger saying it left nothing.
        for (const std::string& path : FolderContents(path_)) {
            if (before_->count(path)) continue;
            const size_t slash = path.rfind('/');
            if (slash == std::string::npos || before_->count(path.substr(0, slash))) fs::remove_all(path_ / path, ec);
        }
        if (!WriteLedger(path_, started_, *before_, std::set<std::string>{})) fs::remove(path_ / kOutputsLedger, ec);
    }
    before_.reset();
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
