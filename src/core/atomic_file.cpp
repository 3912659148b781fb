#include "atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>

#include "error.h"
#include "interrupt.h"

namespace fovrt {

void WriteAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path&)>& write) {
    namespace fs = std::filesystem;
    if (path.has_parent_path()) fs::create_directories(path.parent_path());
    // Unique per writer, also across the hosts of a cluster sharing the filesystem (pids repeat
    // there) and the threads of one process: concurrent writers of one path each write their own
    // temp file, and the last rename wins with a complete file.
    static std::atomic<uint64_t> counter{0};
    char host[256] = "host";
    ::gethostname(host, sizeof host - 1);
    fs::path temp = path;
    temp += ".tmp-" + std::string(host) + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    try {
        write(temp);
        ThrowIfInterrupted();  // an interrupted command renames nothing into place
        fs::rename(temp, path);
    } catch (...) {
        std::error_code ignored;
        fs::remove(temp, ignored);
        throw;
    }
}

void WriteTextAtomically(const std::filesystem::path& path, std::string_view text) {
    WriteAtomically(path, [&](const std::filesystem::path& temp) {
        errno = 0;  // the stream keeps no reason; the failed system call leaves it in errno
        std::ofstream out(temp, std::ios::binary);
        if (!out) Fail("cannot open '{}' for writing: {}", temp.string(), std::strerror(errno));
        out.write(text.data(), std::streamsize(text.size()));
        out.close();
        if (!out) Fail("failed writing '{}': {}", path.string(), std::strerror(errno));
    });
}

}  // namespace fovrt
