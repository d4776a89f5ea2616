// Ctrl-C (SIGINT) and SIGTERM during a long run: the handler only sets a flag; the
// experiment loops poll it and throw Interrupted, so that the staging directory is removed
// by its destructor and the previous result stays as it was.
//
// A step that does not return to a poll soon (one huge scan match, a figure, a write) must
// not leave the signal unanswered: a watchdog thread, woken by the handler through a pipe,
// gives the program `grace_s` to unwind. Past it (or at a second signal) the watchdog
// removes the registered scratch directories and ends the process with status 128 + signal.
#pragma once

#include <stdexcept>
#include <string>

namespace lifelong::eval {

struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted") {}
};

/// Installs the SIGINT/SIGTERM handler and starts the watchdog (idempotent; a later call
/// only changes the grace).
void InstallInterruptHandler(double grace_s = 1.0);
/// True once a signal arrived (or RequestInterrupt was called).
bool InterruptRequested();
/// What the handler does, without the watchdog; tests call it to simulate Ctrl-C.
void RequestInterrupt();
/// Throws Interrupted when a signal arrived.
inline void ThrowIfInterrupted() {
  if (InterruptRequested()) throw Interrupted();
}

/// A directory the watchdog removes when it ends the process (a staging directory); the
/// owner unregisters it once it is renamed into place or removed.
void RegisterScratchDirectory(const std::string& path);
void UnregisterScratchDirectory(const std::string& path);

}  // namespace lifelong::eval
