// SIGINT/SIGTERM as a polled flag, and the watchdog that answers a signal within its grace;
// see interrupt.hpp.
#include "eval/common/interrupt.hpp"

#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <mutex>
#include <set>
#include <thread>

namespace lifelong::eval {
namespace {

volatile std::sig_atomic_t g_interrupted = 0;
int g_pipe[2] = {-1, -1};  // the handler writes the signal number, the watchdog reads
std::atomic<int> g_grace_ms{1000};

std::mutex& ScratchMutex() {
  static std::mutex m;
  return m;
}
std::set<std::string>& Scratch() {
  static std::set<std::string> dirs;
  return dirs;
}

extern "C" void OnSignal(int sig) {
  g_interrupted = 1;
  const unsigned char byte = static_cast<unsigned char>(sig);
  if (g_pipe[1] >= 0) {
    [[maybe_unused]] const ssize_t n = ::write(g_pipe[1], &byte, 1);  // async-signal-safe
  }
}

[[noreturn]] void EndProcess(int sig) {
  {
    std::lock_guard<std::mutex> lock(ScratchMutex());
    for (const std::string& dir : Scratch()) {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  }
  static const char kText[] = "interrupted: the run did not stop within its grace; ended\n";
  [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, kText, sizeof(kText) - 1);
  ::_exit(128 + sig);
}

// Waits for a signal, then for the grace or a second signal, then ends the process. When the
// program unwinds within the grace, main returns and this thread ends with the process.
void Watchdog() {
  unsigned char sig = 0;
  while (::read(g_pipe[0], &sig, 1) != 1) {
  }
  pollfd p{g_pipe[0], POLLIN, 0};
  while (::poll(&p, 1, g_grace_ms.load()) < 0) {  // EINTR: the second signal arrives as a byte
  }
  EndProcess(sig);
}

}  // namespace

void InstallInterruptHandler(double grace_s) {
  g_grace_ms = static_cast<int>(grace_s * 1000.0);
  static std::once_flag once;
  std::call_once(once, [] {
    if (::pipe(g_pipe) == 0) std::thread(Watchdog).detach();
    struct sigaction action {};
    action.sa_handler = OnSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    ::sigaction(SIGINT, &action, nullptr);
    ::sigaction(SIGTERM, &action, nullptr);
  });
}

bool InterruptRequested() { return g_interrupted != 0; }
void RequestInterrupt() { g_interrupted = 1; }

void RegisterScratchDirectory(const std::string& path) {
  std::lock_guard<std::mutex> lock(ScratchMutex());
  Scratch().insert(path);
}

void UnregisterScratchDirectory(const std::string& path) {
  std::lock_guard<std::mutex> lock(ScratchMutex());
  Scratch().erase(path);
}

}  // namespace lifelong::eval
