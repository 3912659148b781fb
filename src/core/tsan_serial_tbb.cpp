// Linked into every executable of a TSan build only (cmake/sanitizers.cmake): TBB (and Embree,
// which schedules its BVH builds through TBB) may use one thread, the caller. Debian's TBB is not
// instrumented, so TSan would report every tbb::parallel_for body as a race between workers it
// cannot see synchronise; with the loops serial, the races TSan reports are between fovrt's own
// threads. Installed at static initialisation, before main and before any arena exists.
#include <tbb/global_control.h>

namespace {
const tbb::global_control serialTbb(tbb::global_control::max_allowed_parallelism, 1);
}  // namespace
