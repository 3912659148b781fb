// CPU time of this process: what a run costs on a shared machine, where wall time depends on
// the load (`fovrt bench`, `experiment`'s manifest and report).
#pragma once

#include <sys/resource.h>

namespace fovrt {

// User + system CPU seconds of this process, all threads (who = RUSAGE_SELF), or of its
// waited-for children (RUSAGE_CHILDREN).
inline double CpuSeconds(int who = RUSAGE_SELF) {
    rusage u{};
    getrusage(who, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace fovrt
