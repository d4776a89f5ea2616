#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "eval/experiment.hpp"

namespace lifelong::eval {
namespace {

// One row per mode, absent figures shown as '-', never as a made-up zero.
TEST(SummaryTable, OneRowPerModeAndDashesForAbsentFigures) {
  const std::string json = R"({"source": "x", "wall_time_s": 1.0, "modes": {
      "pruned": {"observations": 10, "nodes_final": 3, "edges_final": 4, "ate_rmse_m": 0.05,
                 "kld": {"count": 7, "mean": 0.125, "max": 1.0}},
      "standard": {"observations": 10, "nodes_final": 10, "edges_final": 12}}})";
  std::istringstream table(SummaryTable(json));
  std::string header, pruned, standard, extra;
  std::getline(table, header);
  std::getline(table, pruned);
  std::getline(table, standard);
  EXPECT_FALSE(std::getline(table, extra));
  EXPECT_NE(header.find("ATE cm"), std::string::npos);
  EXPECT_NE(pruned.find("pruned"), std::string::npos);
  EXPECT_NE(pruned.find("5.0"), std::string::npos);    // ATE in cm
  EXPECT_NE(pruned.find("0.125"), std::string::npos);  // KL mean
  EXPECT_NE(standard.find(" - "), std::string::npos);
  EXPECT_EQ(standard.find("0.125"), std::string::npos);
}

}  // namespace
}  // namespace lifelong::eval
