// SIGINT/SIGTERM as a polled flag; see interrupt.hpp.
#include "eval/interrupt.hpp"

#include <csignal>

namespace lifelong::eval {
namespace {

volatile std::sig_atomic_t g_interrupted = 0;

// The first signal asks the run to stop cleanly; a second one ends the process at once.
extern "C" void OnSignal(int sig) {
  if (g_interrupted != 0) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
  g_interrupted = 1;
}

}  // namespace

void InstallInterruptHandler() {
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
}

bool InterruptRequested() { return g_interrupted != 0; }
void RequestInterrupt() { g_interrupted = 1; }
void ClearInterrupt() { g_interrupted = 0; }

}  // namespace lifelong::eval
