// Where fovrt reads the data files it ships (scenes/, training/weights/): the installed copy when
// the executable runs from an installation (`cmake --install`: <prefix>/bin/fovrt reads
// <prefix>/share/fovrt), else the source tree it was built from. Shaders need none: they are
// compiled into the executable.
#pragma once

#include <filesystem>

namespace fovrt {

// The installed data folder beside the running executable when it exists, else the source tree.
std::filesystem::path DataRoot();

}  // namespace fovrt
