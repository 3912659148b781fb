// OutputDir: a directory a command writes into, named by its config key (output.dir,
// reference.cache_dir). Created (with its parents) and checked writable before any rendering, so a
// bad path is one line naming the key and the path, not a filesystem exception or a failure after
// minutes of work. A run that fails leaves no trace of its own: the directories this object
// created are removed on destruction unless Keep() was called, and only while they are empty
// (a directory that existed before, or that holds anything, is never touched).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace fovrt {

class OutputDir {
public:
    // Creates `path` and checks that a file can be written in it; fovrt::Error naming `key`
    // and the path otherwise.
    OutputDir(std::filesystem::path path, std::string key);
    ~OutputDir();
    OutputDir(const OutputDir&) = delete;
    OutputDir& operator=(const OutputDir&) = delete;

    const std::filesystem::path& Path() const { return path_; }
    // The command succeeded: keep what it created.
    void Keep() { created_.clear(); }

private:
    void RemoveCreated();

    std::filesystem::path path_;
    std::vector<std::filesystem::path> created_;  // deepest first
};

}  // namespace fovrt
