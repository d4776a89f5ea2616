// libFuzzer target: io::ReadCarmenLog, which reads only from a path (plain or gzipped):
// each input is written to one temporary file per process and read back twice, with
// odometry recovery kAuto and kOn. lifelong::InputError is the expected answer to bad
// input.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "io/carmen_log.hpp"
#include "sensor/input_error.hpp"

namespace {

const std::string& TempPath() {
  static const std::string path = [] {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir != nullptr ? dir : "/tmp") + "/fuzz_carmen_" + std::to_string(getpid()) +
           ".clf";
  }();
  return path;
}

void Read(lifelong::io::OdometryRecovery recovery) {
  lifelong::io::CarmenReadOptions options;
  options.recovery = recovery;
  try {
    lifelong::io::ReadCarmenLog(TempPath(), options);
  } catch (const lifelong::InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::FILE* f = std::fopen(TempPath().c_str(), "wb");
  if (f == nullptr) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  Read(lifelong::io::OdometryRecovery::kAuto);
  Read(lifelong::io::OdometryRecovery::kOn);
  return 0;
}
