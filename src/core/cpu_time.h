// CPU time of this process: what a run costs on a shared machine, where wall time depends on
// the load (`fovrt bench`, `experiment`'s manifest and report); and the wall time of a step.
#pragma once

#include <sys/resource.h>

#include <chrono>

namespace fovrt {

// User + system CPU seconds of this process, all threads (who = RUSAGE_SELF), or of its
// waited-for children (RUSAGE_CHILDREN).
inline double CpuSeconds(int who = RUSAGE_SELF) {
    rusage u{};
    getrusage(who, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Wall-clock milliseconds since `start` (steady clock): the per-step timings of the commands and
// the denoisers.
inline double MsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace fovrt
