#include "app/output_dir.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>
#include <unistd.h>

#include <fmt/format.h>

#include "core/error.h"

namespace fovrt {

namespace fs = std::filesystem;

OutputDir::OutputDir(fs::path path, std::string key) : path_(std::move(path)) {
    if (path_.empty()) Fail("config key '{}': must not be empty", key);
    // Remember which of the path's directories do not exist yet: those are the run's to remove.
    std::error_code ec;
    for (fs::path p = path_; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        created_.push_back(p);
        if (p == p.parent_path()) break;
    }
    auto fail = [&](const std::string& why) {
        Fail("config key '{}': cannot write to '{}': {}", key, path_.string(), why);
    };
    fs::create_directories(path_, ec);
    if (ec) {
        for (const fs::path& p : created_) fs::remove(p, ec);  // the part that did get created
        created_.clear();
        fail(ec.message());
    }
    if (!fs::is_directory(path_, ec)) fail("not a directory");
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

OutputDir::~OutputDir() { RemoveCreated(); }

void OutputDir::RemoveCreated() {
    if (created_.empty()) return;
    std::error_code ec;
    // The directory is new, so everything under it is the run's: empty subdirectories go first,
    // deepest first (files, and the directories holding them, stay).
    std::vector<fs::path> subdirs;
    for (fs::recursive_directory_iterator it(path_, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_directory(ec)) subdirs.push_back(it->path());
    for (auto it = subdirs.rbegin(); it != subdirs.rend(); ++it)
        if (fs::is_empty(*it, ec)) fs::remove(*it, ec);
    for (const fs::path& p : created_) {
        if (!fs::is_directory(p, ec) || !fs::is_empty(p, ec)) break;
        fs::remove(p, ec);
    }
    created_.clear();
}

}  // namespace fovrt
