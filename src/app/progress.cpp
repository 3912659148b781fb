#include "app/progress.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace fovrt {

Progress::Progress(std::string label, int total)
    : label_(std::move(label)), total_(total), start_(std::chrono::steady_clock::now()) {
    enabled_ = ::isatty(STDERR_FILENO) && std::getenv("CI") == nullptr;
}

Progress::~Progress() { Finish(); }

void Progress::Step(const std::string& detail) {
    ++done_;
    if (!enabled_) return;
    constexpr int kWidth = 30;
    int filled = total_ > 0 ? kWidth * done_ / total_ : kWidth;
    double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    double eta = done_ > 0 ? seconds * double(total_ - done_) / double(done_) : 0.0;
    std::fprintf(stderr, "\r%s [%.*s%*s] %d/%d  %.1fs (eta %.0fs) %s\033[K", label_.c_str(),
                 filled, "##############################", kWidth - filled, "", done_, total_,
                 seconds, eta, detail.c_str());
    std::fflush(stderr);
}

void Progress::Finish() {
    if (enabled_ && !finished_) std::fputc('\n', stderr);
    finished_ = true;
}

}  // namespace fovrt
