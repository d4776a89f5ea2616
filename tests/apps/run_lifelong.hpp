// The `lifelong` program run as a whole process, for the tests in tests/apps (LIFELONG_BIN is
// set by tests/apps/CMakeLists.txt).
#pragma once

#include <gtest/gtest.h>
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

/// A path in the test's temporary directory, `prefix` + `name`, removed if it exists.
inline std::filesystem::path FreshPath(const std::string& prefix, const std::string& name) {
  const std::filesystem::path p = std::filesystem::path(::testing::TempDir()) / (prefix + name);
  std::filesystem::remove_all(p);
  return p;
}

/// FreshPath(prefix, name) holding `text`.
inline std::filesystem::path WriteFresh(const std::string& prefix, const std::string& name,
                                        const std::string& text) {
  const std::filesystem::path p = FreshPath(prefix, name);
  std::ofstream(p) << text;
  return p;
}

/// Bad input refused as such: exit 2, `names` (file, line, field) in the message, and no
/// internal error.
inline void ExpectInputError(const Result& r, const std::string& names) {
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find(names), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
}

/// The whole file (empty when it cannot be read).
inline std::string Read(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace lifelong::test
