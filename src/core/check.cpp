#include "check.h"

#include <cstdio>

namespace fovrt::detail {

void CheckFailed(const char* file, int line, const std::string& message) {
    std::fprintf(stderr, "fovrt: internal error: %s:%d: %s\n", file, line, message.c_str());
    std::abort();
}

}  // namespace fovrt::detail
