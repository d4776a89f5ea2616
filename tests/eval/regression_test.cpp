// Map-quality regression tests (issue #6): short scenarios with fixed seeds run through the
// whole pipeline (simulate, map with standard and pruned, evaluate, write the outputs), and
// their metrics must stay within bounds recorded from a good run (docs/results.md). A change
// that makes the maps worse fails here.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "eval/experiment/experiment.hpp"
#include "eval/experiment/simulation.hpp"
#include "eval/truth/world_state.hpp"
#include "sim/scenario.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

// Recorded bounds: a good run's figure with headroom for platform differences.
struct Bounds {
  double max_ate_m;         // trajectory error over every scan
  double max_blur_mean_cm;  // mean distance of occupied cells to the true walls
  double min_recall;        // share of visible true walls in the map
  double max_edges_per_node;
  double max_kept_pct;  // pruned only: share of observations kept as nodes
  double min_loop_precision;
};

nlohmann::json RunScenario(const std::string& name) {
  const sim::Scenario scenario =
      sim::LoadScenario(std::string(LIFELONG_SOURCE_DIR) + "/scenarios/" + name + ".yaml");
  const SimulatedRun run = SimulateScenario(scenario, nullptr);
  EXPECT_TRUE(run.collisions.empty());
  ExperimentConfig config;
  config.out_dir = (fs::temp_directory_path() / ("lifelong_regression_" + name)).string();
  fs::remove_all(config.out_dir);
  config.source = name;
  config.first_pass_s = FirstPassEnd(scenario, run);
  const RunSummary summary =
      RunExperiment(run.observations, TruthOf(scenario.world, run.duration_s), config);
  for (const char* file : {"summary.json", "config.yaml", "standard/trajectory.tum",
                           "pruned/trajectory.tum", "pruned/map.pgm", "truth/map.pgm"}) {
    EXPECT_TRUE(fs::exists(fs::path(config.out_dir) / file)) << file;
  }
  return nlohmann::json::parse(SummaryJsonText(summary));
}

void Check(const nlohmann::json& mode, const Bounds& b, bool pruned) {
  EXPECT_LT(mode["ate_rmse_m"].get<double>(), b.max_ate_m);
  EXPECT_LT(mode["blur"]["mean_cm"].get<double>(), b.max_blur_mean_cm);
  EXPECT_GT(mode["blur"]["recall"].get<double>(), b.min_recall);
  EXPECT_GE(mode["loop_precision"].get<double>(), b.min_loop_precision);
  const double nodes = mode["nodes_final"].get<double>();
  EXPECT_LT(mode["edges_final"].get<double>() / nodes, b.max_edges_per_node);
  if (pruned) {
    EXPECT_LT(mode["scans_kept_pct"].get<double>(), b.max_kept_pct);
    EXPECT_TRUE(mode.contains("kld"));
  } else {
    EXPECT_DOUBLE_EQ(mode["scans_kept_pct"].get<double>(), 100.0);
    EXPECT_FALSE(mode.contains("kld"));
  }
}

TEST(MapQualityRegression, Corridor3) {
  const nlohmann::json s = RunScenario("corridor_3");
  const auto& standard = s["modes"]["standard"];
  const auto& pruned = s["modes"]["pruned"];
  // Recorded at 71689bb (docs/results.md): standard ATE 1.8 cm, blur 2.8 cm, recall 0.89, 1.19 e/n;
  // pruned ATE 4.0 cm, blur 1.8 cm, recall 0.82, 1.28 e/n, 7 % kept.
  // Since the seed split (678ebba): standard ATE 1.9 cm, blur 2.49 cm, recall 0.89,
  // 1.21 e/n; pruned ATE 2.4 cm, blur 2.80 cm, recall 0.84, 1.18 e/n, 7 % kept.
  Check(standard, {0.05, 4.5, 0.78, 1.5, 100.0, 0.95}, false);
  Check(pruned, {0.07, 3.5, 0.72, 2.0, 15.0, 0.95}, true);
  EXPECT_LT(pruned["nodes_final"].get<int>(), standard["nodes_final"].get<int>() / 4);
  // Not "pruned is sharper": on corridor_3 that is a coin toss of the noise draws (over six
  // seeds pruned - standard -0.07 cm [-0.74, 0.61], docs/results.md "The gain threshold"; over
  // seeds 1-5 at 2026-12-05 from -1.21 to +0.66 cm, and +0.58 cm on this scenario's seed). A
  // pruned map much blurrier than standard's on the same stream still fails.
  EXPECT_LT(pruned["blur"]["mean_cm"].get<double>(),
            standard["blur"]["mean_cm"].get<double>() + 1.0);
}

TEST(MapQualityRegression, Office5min) {
  const nlohmann::json s = RunScenario("office_5min");
  const auto& standard = s["modes"]["standard"];
  const auto& pruned = s["modes"]["pruned"];
  // Recorded: standard ATE 5.2 cm, blur 4.1 cm, recall 0.66, 1.11 e/n, precision 0.97;
  // pruned ATE 3.5 cm, blur 3.3 cm, recall 0.69, 1.15 e/n, 43 % kept.
  // Since the seed split (678ebba): standard ATE 2.5 cm, blur 2.35 cm, recall 0.70,
  // 1.11 e/n, precision 1.00; pruned ATE 3.9 cm, blur 2.11 cm, recall 0.71, 1.19 e/n, 54 %
  // kept.
  Check(standard, {0.10, 6.0, 0.58, 1.5, 100.0, 0.90}, false);
  Check(pruned, {0.07, 4.5, 0.58, 2.0, 60.0, 0.90}, true);
  // Not "pruned is sharper" on this one seed: with the matcher's real-odometry defaults
  // (2026-12-04) seed 11 gives 2.44 cm against standard's 1.58, while over seeds 1-5 pruned -
  // standard is -0.24 cm [-0.68, +0.21] (sweeps/twins_10min.yaml, docs/results.md "Sequential
  // matching on real odometry"). A pruned map much blurrier than standard's still fails.
  EXPECT_LT(pruned["blur"]["mean_cm"].get<double>(),
            standard["blur"]["mean_cm"].get<double>() + 1.5);
}

}  // namespace
}  // namespace lifelong::eval
