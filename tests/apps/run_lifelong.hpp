// The `lifelong` program run as a whole process, for the tests in tests/apps (LIFELONG_BIN is
// set by tests/apps/CMakeLists.txt).
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace lifelong::test {

struct Result {
  int code = -1;       ///< exit code, or 128 + signal
  std::string output;  ///< stdout and stderr
};

/// Runs `lifelong ARGS` through the shell and waits for it.
inline Result Lifelong(const std::string& args) {
  const std::string cmd = std::string(LIFELONG_BIN) + " " + args + " 2>&1";
  Result r;
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof(buf), p)) > 0;) r.output.append(buf, n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

/// The whole file (empty when it cannot be read).
inline std::string Read(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace lifelong::test
