// Ctrl-C (SIGINT) and SIGTERM during a long run: the handler only sets a flag; the
// experiment loops poll it and throw Interrupted, so that the staging directory is removed
// by its destructor and the previous result stays as it was.
#pragma once

#include <stdexcept>

namespace lifelong::eval {

struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted") {}
};

/// Installs the SIGINT/SIGTERM handler (idempotent).
void InstallInterruptHandler();
/// True once a signal arrived (or RequestInterrupt was called).
bool InterruptRequested();
/// What the handler does; tests call it to simulate Ctrl-C.
void RequestInterrupt();
/// Clears the flag (tests).
void ClearInterrupt();
/// Throws Interrupted when a signal arrived.
inline void ThrowIfInterrupted() {
  if (InterruptRequested()) throw Interrupted();
}

}  // namespace lifelong::eval
