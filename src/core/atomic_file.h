// Atomic output files: write to "<path>.tmp-<pid>" and rename over <path> only once the content
// is complete, so an interrupted run never leaves a file that looks finished.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace fovrt {

// Calls write(tempPath) and renames the temp file to `path` if it returns without throwing.
// On any exception the temp file is removed and the exception propagates; so it is when a
// SIGINT / SIGTERM arrived meanwhile (core/interrupt.h): Interrupted is thrown, nothing renamed.
void WriteAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path& tempPath)>& write);

// Convenience: writes whole text (or bytes) atomically; a failed write (a full disk) is one
// fovrt::Error naming `path` and the system's reason.
void WriteTextAtomically(const std::filesystem::path& path, std::string_view text);

}  // namespace fovrt
