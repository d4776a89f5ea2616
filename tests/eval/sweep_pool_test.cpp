// The sweep's local process pool (eval/sweep/sweep_pool.hpp): exit codes, logs, and a program
// that cannot be started; and a sweep whose program is gone (eval/sweep/sweep_run.hpp).
#include "eval/sweep/sweep_pool.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "eval/sweep/sweep_run.hpp"
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

// The later jobs would fail alike: none of them starts, and the one already running finishes.
TEST(SweepPool, NoJobStartsAfterOneWhoseProgramCannotStart) {
  const fs::path dir = FreshTempDir("pool_stop");
  const std::string gone = (dir / "gone" / "lifelong").string();
  const auto log = [&dir](const std::string& name) { return (dir / name).string(); };
  PoolOptions options;
  options.parallel = 2;
  const std::vector<PoolJobResult> r =
      RunProcessPool({{{"/bin/sh", "-c", "sleep 0.3; echo done"}, log("running.log")},
                      {{gone, "run"}, log("gone.log")},
                      {{"/bin/sh", "-c", "exit 0"}, log("later1.log")},
                      {{gone, "run"}, log("later2.log")}},
                     options);
  ASSERT_EQ(r.size(), 4u);
  EXPECT_EQ(r[0].exit_code, 0) << "a job that started is not stopped";
  EXPECT_EQ(ReadFileText(log("running.log")), "done\n");
  EXPECT_EQ(r[1].exit_code, 127);
  for (const auto& [i, name] : {std::pair{2u, "later1.log"}, std::pair{3u, "later2.log"}}) {
    EXPECT_FALSE(r[i].started) << i;
    EXPECT_EQ(r[i].exit_code, -1) << i;
    EXPECT_FALSE(fs::exists(log(name))) << i;
  }
}

// A sweep whose program is gone fails one cell, names the others as not started, and says so.
TEST(SweepRun, ASweepWhoseProgramIsGoneStopsAtTheFirstCell) {
  const fs::path dir = FreshTempDir("sweep_gone");
  const fs::path spec = dir / "spec.yaml";
  std::ofstream(spec) << "scenarios: [" << LIFELONG_SOURCE_DIR << "/scenarios/corridor_3.yaml]\n"
                      << "seeds: [1, 2, 3]\nmodes: [standard]\n";
  SweepOptions o;
  o.spec = spec.string();
  o.out_dir = (dir / "out").string();
  o.program = (dir / "gone" / "lifelong").string();
  o.program_id = "test";
  const SweepOutcome r = RunSweep(o);
  EXPECT_EQ(r.cells, 3);
  ASSERT_EQ(r.failed.size(), 1u);
  EXPECT_EQ(r.failed[0].exit_code, 127);
  EXPECT_NE(ReadFileText(r.failed[0].log).find("cannot start " + o.program), std::string::npos);
  EXPECT_EQ(r.not_started.size(), 2u);
  const std::string note = NotStartedNote(r);
  EXPECT_EQ(note.rfind("not started: 2 cells", 0), 0u) << note;
  EXPECT_EQ(NotStartedNote(SweepOutcome{}), "");
  SweepOutcome one;
  one.not_started = {"a"};
  EXPECT_EQ(NotStartedNote(one).rfind("not started: 1 cell,", 0), 0u) << NotStartedNote(one);
}

}  // namespace
}  // namespace lifelong::eval
