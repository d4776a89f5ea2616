// `lifelong sweep` as a whole process (issue #14): bad SPECs stop before anything runs, a
// failed cell does not stop the others, a second sweep runs nothing, and a changed world
// file runs exactly the cells that use it again.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "run_lifelong.hpp"

namespace {

namespace fs = std::filesystem;

using lifelong::test::Lifelong;
using lifelong::test::Read;
using lifelong::test::Result;
const std::string kSource = LIFELONG_SOURCE_DIR;

fs::path Fresh(const std::string& name) {
  const fs::path p = fs::path(::testing::TempDir()) / ("sweep_cli_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

int Lines(const fs::path& p) {
  std::istringstream in(Read(p));
  int n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

// The modification time of every cell's summary.json: a cell that ran again changes it.
std::map<std::string, fs::file_time_type> Stamps(const fs::path& dir) {
  std::map<std::string, fs::file_time_type> out;
  for (const auto& e : fs::directory_iterator(dir / "cells")) {
    if (fs::exists(e.path() / "summary.json")) {
      out[e.path().filename().string()] = fs::last_write_time(e.path() / "summary.json");
    }
  }
  return out;
}

TEST(SweepCli, ABadSpecExitsTwoBeforeAnythingRuns) {
  const fs::path dir = Fresh("bad");
  const fs::path spec = dir / "spec.yaml";
  std::ofstream(spec) << "scenarios: [" << kSource << "/scenarios/corridor_3.yaml]\n"
                      << "modes: [standard]\nsettings:\n  pruning.no_such_key: [1]\n";
  const Result r = Lifelong("sweep " + spec.string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find(spec.string() + ":4: field 'settings.pruning.no_such_key'"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "out")) << "nothing may be written before the SPEC is good";
}

TEST(SweepCli, AFailedCellDoesNotStopTheOthersAndASecondSweepRunsNothing) {
  const fs::path dir = Fresh("resume");
  // A scenario like corridor_3 whose world file is broken, and a corrupt log.
  std::string scenario = Read(kSource + "/scenarios/corridor_3.yaml");
  scenario.replace(scenario.find("../worlds/corridor.yaml"), 23, "broken_world.yaml");
  std::ofstream(dir / "broken.yaml") << scenario;
  std::ofstream(dir / "broken_world.yaml") << "walls: [[[0, 0], [1, oops\n";
  std::ofstream(dir / "corrupt.clf") << "ROBOTLASER1 not a number\n";
  const fs::path spec = dir / "spec.yaml";
  std::ofstream(spec) << "scenarios: [" << kSource << "/scenarios/corridor_3.yaml, broken.yaml]\n"
                      << "logs: [{log: corrupt.clf}]\nseeds: [1, 2]\nmodes: [standard]\n";
  const fs::path out = dir / "out";
  const std::string sweep = "sweep " + spec.string() + " -o " + out.string() + " -j 2";

  Result r = Lifelong(sweep);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("ran 5 of 5 cells"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sweep 5/5 cells, 3 failed"), std::string::npos) << r.output;
  const fs::path broken_log = out / "cells" / "broken-seed1.run.log";
  EXPECT_NE(r.output.find("failed: broken-seed1 (exit 2), log " + broken_log.string()),
            std::string::npos)
      << r.output;
  EXPECT_NE(Read(broken_log).find("broken_world.yaml"), std::string::npos) << Read(broken_log);
  EXPECT_NE(r.output.find("failed: corrupt (exit 2)"), std::string::npos) << r.output;
  // The good cells' results are collected: 2 runs and one aggregate row with n = 2.
  EXPECT_EQ(Lines(out / "runs.csv"), 3);
  EXPECT_EQ(Lines(out / "aggregate.csv"), 2);
  EXPECT_NE(Read(out / "aggregate.csv").find(",standard,2,"), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "report.html"));
  const auto first = Stamps(out);
  ASSERT_EQ(first.size(), 2u);

  // Repair the world and the log: only those cells run again.
  fs::copy_file(kSource + "/worlds/corridor.yaml", dir / "broken_world.yaml",
                fs::copy_options::overwrite_existing);
  const Result sim = Lifelong("simulate " + kSource + "/scenarios/corridor_3.yaml -o " +
                              (dir / "corrupt.clf").string());
  ASSERT_EQ(sim.code, 0) << sim.output;
  r = Lifelong(sweep);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("ran 3 of 5 cells (2 up to date)"), std::string::npos) << r.output;
  const auto second = Stamps(out);
  ASSERT_EQ(second.size(), 5u);
  for (const auto& [cell, time] : first) EXPECT_EQ(second.at(cell), time) << cell << " ran again";
  EXPECT_EQ(Lines(out / "runs.csv"), 6);

  // Nothing changed: nothing runs, every result stays as it was.
  r = Lifelong(sweep);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("ran 0 of 5 cells (5 up to date)"), std::string::npos) << r.output;
  EXPECT_EQ(Stamps(out), second);

  // collect alone gives the same tables.
  const std::string runs = Read(out / "runs.csv");
  fs::remove(out / "runs.csv");
  r = Lifelong("sweep collect " + out.string());
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(Read(out / "runs.csv"), runs);
}

TEST(SweepCli, AnOutputDirectoryThatHoldsNoSweepIsRefused) {
  const fs::path dir = Fresh("refuse");
  std::ofstream(dir / "precious.txt") << "keep";
  std::ofstream(dir / "spec.yaml")
      << "scenarios: [" << kSource << "/scenarios/corridor_3.yaml]\nmodes: [standard]\n";
  const Result r = Lifelong("sweep " + (dir / "spec.yaml").string() + " -o " + dir.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("holds no sweep"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "cells"));
}

// `sweep run-cell DIR INDEX` is what a Slurm array task runs (eval/sweep/sweep_slurm.hpp): the
// cell's command from sweep.json, its log and its stamp, nothing when it is up to date, and
// never a plan written by another program.
TEST(SweepCli, RunCellRunsOneCellOfThePlanAsThePoolDoes) {
  const fs::path dir = Fresh("run_cell");
  std::ofstream(dir / "spec.yaml")
      << "scenarios: [" << kSource
      << "/scenarios/corridor_3.yaml]\nseeds: [4]\nmodes: [standard]\n";
  const fs::path out = dir / "out";
  Result r = Lifelong("sweep " + (dir / "spec.yaml").string() + " -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path cell = out / "cells" / "corridor_3-seed4";
  const std::string summary = Read(cell / "summary.json");
  const auto summary_time = fs::last_write_time(cell / "summary.json");
  const std::string stamp = Read(cell / "sweep_cell.json");
  ASSERT_FALSE(stamp.empty());

  r = Lifelong("sweep run-cell " + out.string() + " 0");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("cell corridor_3-seed4 is up to date"), std::string::npos) << r.output;

  fs::remove(cell / "sweep_cell.json");
  fs::remove(out / "cells" / "corridor_3-seed4.run.log");
  r = Lifelong("sweep run-cell " + out.string() + " 0");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(Read(cell / "sweep_cell.json"), stamp);
  EXPECT_TRUE(fs::exists(out / "cells" / "corridor_3-seed4.run.log"));
  // It ran again (a new summary.json) with the same inputs: the same graph.
  const auto nodes = [](const std::string& json) {
    const std::size_t at = json.find("\"nodes_final\"");
    return at == std::string::npos ? std::string() : json.substr(at, json.find(',', at) - at);
  };
  EXPECT_FALSE(nodes(summary).empty());
  EXPECT_EQ(nodes(Read(cell / "summary.json")), nodes(summary));
  EXPECT_NE(fs::last_write_time(cell / "summary.json"), summary_time);

  r = Lifelong("sweep run-cell " + out.string() + " 1");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("has no cell 1 (it has 1)"), std::string::npos) << r.output;

  std::string plan = Read(out / "sweep.json");
  const std::size_t at = plan.find("\"program_id\": \"") + 15;
  plan.insert(at, "other ");
  std::ofstream(out / "sweep.json") << plan;
  r = Lifelong("sweep run-cell " + out.string() + " 0");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("the plan was written by lifelong other "), std::string::npos)
      << r.output;
}

TEST(SweepCli, SlurmOptionsNeedSlurm) {
  const Result r = Lifelong("sweep spec.yaml -o out --no-wait");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("need --slurm"), std::string::npos) << r.output;
}

}  // namespace
