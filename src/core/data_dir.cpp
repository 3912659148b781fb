#include "core/data_dir.h"

#include <system_error>

namespace fovrt {

std::filesystem::path DataRoot() {
    // FOVRT_INSTALLED_DATA: the data folder relative to the executable's folder, from the install
    // rules (CMakeLists.txt), so the two cannot disagree.
    std::error_code error;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) {
        const std::filesystem::path installed = exe.parent_path() / FOVRT_INSTALLED_DATA;
        if (std::filesystem::is_directory(installed / "scenes", error)) return installed.lexically_normal();
    }
    return FOVRT_SOURCE_DIR;
}

}  // namespace fovrt
