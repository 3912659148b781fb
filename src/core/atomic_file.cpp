#include "atomic_file.h"

#include <unistd.h>

#include <fstream>

#include "error.h"

namespace fovrt {

void WriteAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path&)>& write) {
    namespace fs = std::filesystem;
    if (path.has_parent_path()) fs::create_directories(path.parent_path());
    fs::path temp = path;
    temp += ".tmp-" + std::to_string(::getpid());
    try {
        write(temp);
        fs::rename(temp, path);
    } catch (...) {
        std::error_code ignored;
        fs::remove(temp, ignored);
        throw;
    }
}

void WriteTextAtomically(const std::filesystem::path& path, const std::string& text) {
    WriteAtomically(path, [&](const std::filesystem::path& temp) {
        std::ofstream out(temp, std::ios::binary);
        if (!out) Fail("cannot open '{}' for writing", temp.string());
        out << text;
        out.close();
        if (!out) Fail("failed writing '{}'", temp.string());
    });
}

}  // namespace fovrt
