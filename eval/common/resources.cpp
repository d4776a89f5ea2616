#include "eval/common/resources.hpp"

#include <fcntl.h>
#include <malloc.h>
#include <unistd.h>

#include <charconv>
#include <cstdint>
#include <fstream>
#include <sstream>

namespace lifelong::eval {

bool ResetPeakRss() {
  malloc_trim(0);
  std::ofstream clear("/proc/self/clear_refs");
  if (!clear) return false;
  clear << "5";
  return static_cast<bool>(clear.flush());
}

namespace {

/// Value in kB of a "Key:   1234 kB" line of /proc/self/status, in MB.
std::optional<double> StatusMb(const std::string& key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, key.size() + 1, key + ":") != 0) continue;
    std::istringstream fields(line.substr(key.size() + 1));
    double kb = 0.0;
    if (fields >> kb) return kb / 1024.0;
    return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace

// /proc/self/statm ("size resident shared ...", in pages) holds the same count as VmRSS in
// /proc/self/status, and costs the kernel far less to produce: a run reads it once per
// observation, and the status file cost about 1 % of an office_5min run.
std::optional<double> CurrentRssMb() {
  const int fd = ::open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  char text[128];
  const ssize_t n = ::read(fd, text, sizeof text);
  ::close(fd);
  if (n <= 0) return std::nullopt;
  const char* const end = text + n;
  std::uint64_t size = 0, resident = 0;
  auto [next, error] = std::from_chars(text, end, size);
  if (error != std::errc() || next == end || *next != ' ') return std::nullopt;
  if (std::from_chars(next + 1, end, resident).ec != std::errc()) return std::nullopt;
  const long page = ::sysconf(_SC_PAGESIZE);
  if (page <= 0) return std::nullopt;
  return static_cast<double>(resident) * static_cast<double>(page) / (1024.0 * 1024.0);
}

std::optional<double> PeakRssMb() { return StatusMb("VmHWM"); }

std::string CpuModelName() {
  std::ifstream in("/proc/cpuinfo");
  std::string line, model;
  int cpus = 0;
  while (std::getline(in, line)) {
    if (line.compare(0, 9, "processor") == 0) ++cpus;
    if (model.empty() && line.compare(0, 10, "model name") == 0) {
      const auto colon = line.find(':');
      const auto start =
          colon == std::string::npos ? colon : line.find_first_not_of(" \t", colon + 1);
      if (start != std::string::npos) model = line.substr(start);
    }
  }
  if (model.empty()) return "unknown";
  return model + " (" + std::to_string(cpus) + " CPUs)";
}

}  // namespace lifelong::eval
