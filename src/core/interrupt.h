// Interrupts: SIGINT / SIGTERM end a batch command cleanly instead of killing it mid-write.
// The handler only records the signal (async-signal-safe); the command notices it where stopping
// is safe (frame boundaries, and WriteAtomically before it renames a temporary into place) and
// throws Interrupted, so every temporary is removed on the way out, no manifest is written, and
// main() prints one line and exits 128 + the signal (130 for SIGINT, 143 for SIGTERM). A second
// signal of the same kind kills at once (the default action is restored by the first).
#pragma once

#include <string>

#include "core/error.h"

namespace fovrt {

// Thrown at the first safe point after a signal. what() says what the command left behind.
class Interrupted : public Error {
public:
    Interrupted(int signal, const std::string& message) : Error(message), signal_(signal) {}
    int Signal() const { return signal_; }
    int ExitCode() const { return 128 + signal_; }

private:
    int signal_;
};

// Installs the SIGINT / SIGTERM handlers for its lifetime (batch commands: run, experiment,
// reference, dataset); the live preview and OpenXR sessions keep their own handling.
class InterruptScope {
public:
    InterruptScope();
    ~InterruptScope();
    InterruptScope(const InterruptScope&) = delete;
    InterruptScope& operator=(const InterruptScope&) = delete;
};

// The signal received since the scope began, or 0.
int PendingInterrupt();
// Throws Interrupted ("interrupted by SIGINT") when a signal is pending.
void ThrowIfInterrupted();
// "SIGINT", "SIGTERM".
std::string SignalName(int signal);

}  // namespace fovrt
