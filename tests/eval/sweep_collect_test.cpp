// `sweep collect` alone, on fabricated cell directories: runs.csv, aggregate.csv and
// paired.csv hold what the cells' summary.json files say, empty where a figure is absent.
#include "eval/sweep/sweep_collect.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "eval/figures/plots.hpp"
#include "eval/sweep/sweep_report.hpp"
#include "eval/sweep/sweep_run.hpp"
#include "sensor/input_error.hpp"
#include "test_files.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<std::vector<std::string>> Csv(const fs::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(ReadFileText(p));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> row;
    std::string cell;
    std::istringstream ls(line);
    while (std::getline(ls, cell, ',')) row.push_back(cell);
    if (!line.empty() && line.back() == ',') row.push_back("");
    rows.push_back(row);
  }
  return rows;
}

// The column named `name` of row `r`.
std::string At(const std::vector<std::vector<std::string>>& t, std::size_t r,
               const std::string& name) {
  for (std::size_t c = 0; c < t[0].size(); ++c) {
    if (t[0][c] == name) return c < t[r].size() ? t[r][c] : "";
  }
  ADD_FAILURE() << "no column " << name;
  return "?";
}

void WriteCell(const fs::path& dir, const SweepPlanCell& cell, const json& modes,
               bool stamped = true) {
  const fs::path d = dir / "cells" / cell.name;
  fs::create_directories(d);
  std::ofstream(d / "summary.json") << json{{"source", cell.source}, {"modes", modes}}.dump();
  if (stamped) std::ofstream(d / kCellStampFile) << json{{"hash", cell.hash}}.dump();
}

// Two seeds × one setting value × {standard, pruned}, and a third seed whose result is
// from other inputs (stale hash): it must not be read.
fs::path Fabricate() {
  // One folder per test: CTest runs the tests of this file in parallel processes.
  const fs::path dir = fs::path(::testing::TempDir()) /
                       (std::string("sweep_collect_") +
                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  SweepPlan plan{"spec.yaml", {"standard", "pruned"}, "standard", {"pruning.radius_m"}, {}, ""};
  for (int seed : {1, 2, 3}) {
    plan.cells.push_back({"c" + std::to_string(seed),
                          "corridor_3.yaml",
                          false,
                          seed,
                          {{"pruning.radius_m", "2.5"}},
                          "h" + std::to_string(seed),
                          {},
                          ""});
  }
  std::ofstream(dir / "sweep.json") << SweepPlanToJson(plan);
  // seed 1: standard 10 nodes, pruned 6; blur only in standard; seed 2: 14 / 7.
  WriteCell(dir, plan.cells[0],
            {{"standard",
              {{"nodes_final", 10},
               {"blur", {{"mean_cm", 2.0}, {"recall", 0.5}}},
               {"note", "text"},
               {"flag", true}}},
             {"pruned", {{"nodes_final", 6}, {"ate_rmse_m", 0.25}}}});
  WriteCell(dir, plan.cells[1],
            {{"standard", {{"nodes_final", 14}, {"blur", {{"mean_cm", 4.0}}}}},
             {"pruned", {{"nodes_final", 7}, {"ate_rmse_m", 0.5}}}});
  SweepPlanCell stale = plan.cells[2];
  stale.hash = "other";
  WriteCell(dir, stale, {{"standard", {{"nodes_final", 999}}}, {"pruned", {{"nodes_final", 999}}}});
  return dir;
}

TEST(SweepCollect, RunsCsvHasOneRowPerCellAndModeAndEmptyWhereAbsent) {
  const fs::path dir = Fabricate();
  const SweepTables t = CollectSweep(dir.string());
  EXPECT_EQ(t.missing, std::vector<std::string>{"c3"});
  const auto runs = Csv(dir / "runs.csv");
  ASSERT_EQ(runs.size(), 5u);  // header + 2 cells × 2 modes
  EXPECT_EQ(runs[0],
            (std::vector<std::string>{"cell", "source", "seed", "mode", "pruning.radius_m",
                                      "blur/mean_cm", "blur/recall", "nodes_final", "ate_rmse_m"}));
  EXPECT_EQ(runs[1], (std::vector<std::string>{"c1", "corridor_3.yaml", "1", "standard", "2.5", "2",
                                               "0.5", "10", ""}));
  EXPECT_EQ(runs[2], (std::vector<std::string>{"c1", "corridor_3.yaml", "1", "pruned", "2.5", "",
                                               "", "6", "0.25"}));
  EXPECT_EQ(At(runs, 3, "blur/recall"), "");  // seed 2 has no recall: empty, not 0
  EXPECT_EQ(ReadFileText(dir / "runs.csv").find("999"), std::string::npos)
      << "a stale cell was read";
}

TEST(SweepCollect, AggregateHasMeanStdAndTIntervalOverSeeds) {
  const fs::path dir = Fabricate();
  CollectSweep(dir.string());
  const auto agg = Csv(dir / "aggregate.csv");
  ASSERT_EQ(agg.size(), 3u);
  EXPECT_EQ(At(agg, 1, "mode"), "standard");
  EXPECT_EQ(At(agg, 1, "n"), "2");
  // standard nodes {10, 14}: mean 12, s = sqrt(8) = 2.828..., half = 12.7062 * s / sqrt(2).
  EXPECT_EQ(At(agg, 1, "nodes_final/mean"), "12");
  EXPECT_NEAR(std::stod(At(agg, 1, "nodes_final/std")), std::sqrt(8.0), 1e-12);
  EXPECT_NEAR(std::stod(At(agg, 1, "nodes_final/ci95_low")), 12 - 12.7062047362 * 2, 1e-8);
  EXPECT_NEAR(std::stod(At(agg, 1, "nodes_final/ci95_high")), 12 + 12.7062047362 * 2, 1e-8);
  // blur/recall from one seed only: a mean, n = 1, no spread, no interval.
  EXPECT_EQ(At(agg, 1, "blur/recall/mean"), "0.5");
  EXPECT_EQ(At(agg, 1, "blur/recall/n"), "1");
  EXPECT_EQ(At(agg, 1, "blur/recall/std"), "");
  EXPECT_EQ(At(agg, 1, "blur/recall/ci95_low"), "");
  // pruned has no blur at all.
  EXPECT_EQ(At(agg, 2, "mode"), "pruned");
  EXPECT_EQ(At(agg, 2, "blur/mean_cm/mean"), "");
  EXPECT_EQ(At(agg, 2, "blur/mean_cm/n"), "");
  EXPECT_EQ(At(agg, 2, "ate_rmse_m/mean"), "0.375");
}

TEST(SweepCollect, PairedIsTheDifferenceToTheBaselinePerSeed) {
  const fs::path dir = Fabricate();
  CollectSweep(dir.string());
  const auto paired = Csv(dir / "paired.csv");
  ASSERT_EQ(paired.size(), 2u);  // pruned − standard only
  EXPECT_EQ(At(paired, 1, "mode"), "pruned");
  EXPECT_EQ(At(paired, 1, "baseline"), "standard");
  // differences {6 − 10, 7 − 14} = {−4, −7}: mean −5.5, s = sqrt(4.5).
  EXPECT_EQ(At(paired, 1, "nodes_final/mean"), "-5.5");
  EXPECT_NEAR(std::stod(At(paired, 1, "nodes_final/std")), std::sqrt(4.5), 1e-12);
  EXPECT_NEAR(std::stod(At(paired, 1, "nodes_final/ci95_high")),
              -5.5 + 12.7062047362 * std::sqrt(4.5) / std::sqrt(2.0), 1e-8);
  // ate only in pruned, blur only in standard: no difference exists.
  EXPECT_EQ(At(paired, 1, "ate_rmse_m/mean"), "");
  EXPECT_EQ(At(paired, 1, "blur/mean_cm/mean"), "");
}

TEST(SweepCollect, ReportLinksTablesAndCells) {
  const fs::path dir = Fabricate();
  CollectSweep(dir.string());
  const std::string html = ReadFileText(dir / "report.html");
  EXPECT_NE(html.find("aggregate.csv"), std::string::npos);
  EXPECT_NE(html.find("cells/c1/report.html"), std::string::npos);
  EXPECT_NE(html.find("c3"), std::string::npos) << "the missing cell is named";
  std::string terminal;
  if (GnuplotAvailable("gnuplot", &terminal)) {
    EXPECT_TRUE(fs::exists(dir / "sweep_nodes_final.png"));
    EXPECT_NE(html.find("sweep_nodes_final.png"), std::string::npos);
  }
}

TEST(SweepCollect, ADirectoryWithoutAPlanIsAnInputError) {
  const fs::path dir = fs::path(::testing::TempDir()) / "sweep_collect_empty";
  fs::create_directories(dir);
  EXPECT_THROW(CollectSweep(dir.string()), InputError);
}

}  // namespace
}  // namespace lifelong::eval
