#include "core/interrupt.h"

#include <signal.h>

#include <atomic>

namespace fovrt {
namespace {

// Lock-free, so the handler may store to it.
std::atomic<int> pending{0};
static_assert(std::atomic<int>::is_always_lock_free);

struct sigaction previousInt, previousTerm;

extern "C" void RecordSignal(int signal) { pending.store(signal, std::memory_order_relaxed); }

}  // namespace

InterruptScope::InterruptScope() {
    pending.store(0);
    struct sigaction action {};
    action.sa_handler = RecordSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;  // a second signal kills at once
    sigaction(SIGINT, &action, &previousInt);
    sigaction(SIGTERM, &action, &previousTerm);
}

InterruptScope::~InterruptScope() {
    sigaction(SIGINT, &previousInt, nullptr);
    sigaction(SIGTERM, &previousTerm, nullptr);
}

int PendingInterrupt() { return pending.load(std::memory_order_relaxed); }

std::string SignalName(int signal) {
    switch (signal) {
        case SIGINT: return "SIGINT";
        case SIGTERM: return "SIGTERM";
        default: return "signal " + std::to_string(signal);
    }
}

void ThrowIfInterrupted() {
    if (int signal = PendingInterrupt()) throw Interrupted(signal, "interrupted by " + SignalName(signal));
}

}  // namespace fovrt
