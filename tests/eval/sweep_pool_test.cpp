// The sweep's local process pool (eval/sweep/sweep_pool.hpp): exit codes, logs, and a program
// that cannot be started.
#include "eval/sweep/sweep_pool.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include "test_files.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

TEST(SweepPool, AJobsExitCodeAndOutputAreKept) {
  const fs::path dir = FreshTempDir("pool_exit");
  const std::string log = (dir / "a.log").string();
  const std::vector<PoolJobResult> r =
      RunProcessPool({{{"/bin/sh", "-c", "echo out; echo err >&2; exit 3"}, log}}, {});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_TRUE(r[0].started);
  EXPECT_EQ(r[0].exit_code, 3);
  EXPECT_EQ(ReadFileText(log), "out\nerr\n");
}

// The bug: a sweep whose program was rebuilt under it failed every later cell with exit 127
// and an empty log; the log now names the program and the reason.
TEST(SweepPool, AProgramThatCannotStartSaysWhyInItsLog) {
  const fs::path dir = FreshTempDir("pool_missing");
  const std::string program = (dir / "gone" / "lifelong").string();
  const std::string log = (dir / "b.log").string();
  const std::vector<PoolJobResult> r = RunProcessPool({{{program, "run"}, log}}, {});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].exit_code, 127);
  const std::string text = ReadFileText(log);
  EXPECT_NE(text.find("cannot start " + program), std::string::npos) << text;
  EXPECT_NE(text.find("No such file or directory"), std::string::npos) << text;
}

}  // namespace
}  // namespace lifelong::eval
