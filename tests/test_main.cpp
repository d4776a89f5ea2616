// main() of every gtest binary: each process gets a temporary directory of its own.
//
// ctest runs each test case of a binary as its own process, two at a time, so fixed names
// under /tmp (a report directory, a graph file) would be shared by cases that run at once
// and race. Here TMPDIR (std::filesystem::temp_directory_path) and TEST_TMPDIR
// (::testing::TempDir) point into a fresh mkdtemp directory, removed at exit.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>

int main(int argc, char** argv) {
  const char* base = std::getenv("TMPDIR");
  std::string pattern = std::string(base && *base ? base : "/tmp") + "/lifelong_test_XXXXXX";
  if (mkdtemp(pattern.data()) == nullptr) {
    std::perror(("cannot create a temporary directory from " + pattern).c_str());
    return 1;
  }
  setenv("TMPDIR", pattern.c_str(), 1);
  setenv("TEST_TMPDIR", pattern.c_str(), 1);
  ::testing::InitGoogleTest(&argc, argv);
  const int result = RUN_ALL_TESTS();
  std::error_code ignored;
  std::filesystem::remove_all(pattern, ignored);
  return result;
}
