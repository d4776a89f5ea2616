// The end-of-run console table (eval/report/console_table.hpp).
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "eval/report/console_table.hpp"

namespace lifelong::eval {
namespace {

std::vector<std::string> Lines(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

RunSummary TwoModes() {
  RunSummary s;
  ModeSummary standard, pruned;
  standard.observations = pruned.observations = 10;
  standard.nodes_final = 10;
  standard.edges_final = 12;
  standard.wall_time_s = 4.0;
  standard.time_per_obs_ms = TimeStats{2.0, 2.0, 3.0, 4.0, std::nullopt, 8.0};
  pruned.nodes_final = 3;
  pruned.edges_final = 4;
  pruned.wall_time_s = 2.0;
  pruned.time_per_obs_ms = TimeStats{1.0, 1.0, 1.5, 2.0, std::nullopt, 2.0};
  pruned.ate_rmse_m = 0.05;
  pruned.kld = KldSummary{7, 0.125, 1.0};
  s.modes = {{"standard", standard}, {"pruned", pruned}};
  s.mode_order = {"standard", "pruned"};
  return s;
}

// Rows in --modes order (the baseline first, not by name), headers with units, ratios to
// the baseline, and absent figures as '-', never a made-up zero.
TEST(ConsoleTable, ModesInOrderWithUnitsRatiosAndDashes) {
  const std::vector<std::string> lines = Lines(ConsoleTable(TwoModes()));
  ASSERT_EQ(lines.size(), 3u);
  const std::string& header = lines[0];
  for (const char* h : {"last 10 % [ms/obs]", "KL [nats]", "ATE [m]", "wall / base",
                        "last 10 % / base", "wall [s]"}) {
    EXPECT_NE(header.find(h), std::string::npos) << h;
  }
  EXPECT_EQ(header.find("blur"), std::string::npos);  // no mode has it: no column
  EXPECT_EQ(lines[1].rfind("standard (base)", 0), 0u);
  EXPECT_EQ(lines[2].rfind("pruned", 0), 0u);
  EXPECT_NE(lines[2].find("0.50"), std::string::npos);   // wall 2 s / 4 s
  EXPECT_NE(lines[2].find("0.25"), std::string::npos);   // last 10 %: 2 / 8
  EXPECT_NE(lines[2].find("0.050"), std::string::npos);  // ATE in m, as in the JSON
  EXPECT_NE(lines[2].find("0.125"), std::string::npos);  // KL mean
  EXPECT_NE(lines[1].find(" - "), std::string::npos);    // standard has no ATE or KL
  EXPECT_NE(lines[1].find("1.00"), std::string::npos);   // the baseline's own ratio
}

TEST(ConsoleTable, OrderFollowsModeOrderNotNames) {
  RunSummary s = TwoModes();
  s.mode_order = {"pruned", "standard"};
  const std::vector<std::string> lines = Lines(ConsoleTable(s));
  EXPECT_EQ(lines[1].rfind("pruned (base)", 0), 0u);
  EXPECT_NE(lines[2].find("2.00"), std::string::npos);  // standard's wall is 2x pruned's
}

TEST(ConsoleTable, OneModeHasNoRatioColumns) {
  RunSummary s = TwoModes();
  s.modes.erase("pruned");
  s.mode_order = {"standard"};
  const std::vector<std::string> lines = Lines(ConsoleTable(s));
  EXPECT_EQ(lines[0].find("/ base"), std::string::npos);
  EXPECT_EQ(lines[1].find("(base)"), std::string::npos);
}

}  // namespace
}  // namespace lifelong::eval
