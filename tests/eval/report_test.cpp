// The output contract: exact JSON keys, CSV header, absent figures, atomic writes
// (report.html: report_html_test.cpp).
#include "eval/metrics/summary.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "test_files.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

std::vector<TimelineRow> Rows(int n) {
  std::vector<TimelineRow> rows;
  for (int i = 0; i < n; ++i) {
    TimelineRow r;
    r.obs = i, r.t_s = 0.5 * i, r.time_ms = i + 1.0, r.nodes = 10 + i, r.edges = 20 - i;
    r.gamma = 0.25, r.rss_mb = 100.0 + (i == 3 ? 50 : 0), r.graph_bytes = 1000u + i;
    r.loop_closures = i / 4;
    rows.push_back(r);
  }
  return rows;
}

std::set<std::string> Keys(const nlohmann::json& j) {
  std::set<std::string> k;
  for (auto it = j.begin(); it != j.end(); ++it) k.insert(it.key());
  return k;
}

TEST(TimeStatsTest, HandComputedOnOneToTwenty) {
  const auto t = ComputeTimeStats(Rows(20), 5);  // time_ms = 1..20
  ASSERT_TRUE(t.has_value());
  EXPECT_DOUBLE_EQ(t->mean, 10.5);
  EXPECT_DOUBLE_EQ(t->p50, 10.5);
  EXPECT_DOUBLE_EQ(t->p95, 19.05);
  EXPECT_DOUBLE_EQ(t->max, 20.0);
  EXPECT_DOUBLE_EQ(*t->first_pass_mean, 3.0);  // obs 0..4
  EXPECT_DOUBLE_EQ(t->last10_mean, 19.5);      // last 2 of 20
  EXPECT_FALSE(ComputeTimeStats(Rows(20), std::nullopt)->first_pass_mean.has_value());
  EXPECT_FALSE(ComputeTimeStats({}, 5).has_value());
}

TEST(SummarizeTimelineTest, FinalMaxAndFirstPass) {
  const ModeSummary m = SummarizeTimeline(Rows(20), 5);
  EXPECT_EQ(*m.observations, 20);
  EXPECT_EQ(*m.nodes_final, 29);
  EXPECT_EQ(*m.nodes_max, 29);
  EXPECT_EQ(*m.edges_final, 1);
  EXPECT_EQ(*m.edges_max, 20);
  EXPECT_EQ(*m.nodes_after_first_pass, 14);  // row obs = 4
  EXPECT_EQ(*m.graph_bytes_final, 1019);
  EXPECT_DOUBLE_EQ(*m.peak_rss_mb, 150.0);
  EXPECT_FALSE(m.blur.has_value());
  EXPECT_FALSE(m.ate_rmse_m.has_value());
}

TEST(SummaryJsonTest, ContainsExactlyTheContractNames) {
  RunSummary s;
  s.source = "scenarios/corridor_100.yaml";
  s.seed = 7;
  s.wall_time_s = 12.5;
  s.log_duration_s = 800.0;
  ModeSummary full = SummarizeTimeline(Rows(20), 5);
  full.wall_time_s = 3.0;
  full.scans_kept_pct = 40.0;
  full.blur = BlurSummary{2.0, 5.0, 21.0, 0.9};
  full.ate_rmse_m = 0.1, full.loop_precision = 1.0, full.loop_recall = 0.5;
  full.relations = RelationsSummary{10, 0.1, 0.01, 1.0, 0.1};
  full.kld = SummarizeKld({0.5, 1.5});
  full.map_entropy_bits = 1234.0, full.occupied_share = 0.1;
  full.edges_by_kind = {{"odometry", 3}, {"marginal", 4}};
  s.modes["chow_liu"] = full;
  s.modes["standard"].observations = 20;
  s.modes["standard"].ate_rmse_m = std::numeric_limits<double>::quiet_NaN();  // never written

  const fs::path dir = FreshTempDir("json");
  WriteSummaryJson((dir / "summary.json").string(), s);
  EXPECT_FALSE(fs::exists(io::TempPathFor((dir / "summary.json").string())));
  const auto j = nlohmann::json::parse(ReadFileText(dir / "summary.json"));
  EXPECT_EQ(Keys(j),
            (std::set<std::string>{"source", "seed", "wall_time_s", "log_duration_s", "modes"}));
  EXPECT_EQ(j["seed"], 7);
  const auto& m = j["modes"]["chow_liu"];
  EXPECT_EQ(Keys(m),
            (std::set<std::string>{
                "observations", "wall_time_s", "time_per_obs_ms", "nodes_final", "edges_final",
                "nodes_max", "edges_max", "nodes_after_first_pass", "gamma_final", "scans_kept_pct",
                "peak_rss_mb", "graph_bytes_final", "blur", "ate_rmse_m", "loop_precision",
                "loop_recall", "relations", "kld", "map_entropy_bits", "occupied_share",
                // our extensions of the contract (docs/output-contract.md)
                "edges_by_kind", "stage_ms"}));
  EXPECT_EQ(m["edges_by_kind"]["marginal"], 4);
  EXPECT_EQ(Keys(m["time_per_obs_ms"]),
            (std::set<std::string>{"mean", "p50", "p95", "max", "first_pass_mean", "last10_mean"}));
  EXPECT_EQ(Keys(m["blur"]), (std::set<std::string>{"mean_cm", "p95_cm", "thickness", "recall"}));
  EXPECT_EQ(Keys(m["relations"]), (std::set<std::string>{"count", "trans_mean_m", "trans_std_m",
                                                         "rot_mean_deg", "rot_std_deg"}));
  EXPECT_EQ(Keys(m["kld"]),
            (std::set<std::string>{"count", "mean", "max", "infinite", "mean_finite"}));
  EXPECT_EQ(m["kld"]["infinite"], 0);
  EXPECT_EQ(m["kld"]["count"], 2);
  EXPECT_DOUBLE_EQ(m["kld"]["mean"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(m["time_per_obs_ms"]["p95"].get<double>(), 19.05);
  // figures that do not apply are absent, not zero
  EXPECT_EQ(Keys(j["modes"]["standard"]), (std::set<std::string>{"observations"}));
}

// An approximation that loses a direction outright has an infinite KL: the mean and the
// maximum are then infinite (null in JSON), and how many there were, and the mean of the
// rest, are said beside them instead of leaving a bare null.
TEST(SummarizeKldTest, InfiniteDivergencesAreCountedBesideTheFiniteMean) {
  const double inf = std::numeric_limits<double>::infinity();
  const KldSummary k = *SummarizeKld({0.5, inf, 1.5, inf});
  EXPECT_EQ(k.count, 4);
  EXPECT_EQ(k.infinite, 2);
  EXPECT_DOUBLE_EQ(k.mean_finite, 1.0);
  EXPECT_TRUE(std::isinf(k.mean));
  EXPECT_TRUE(std::isinf(k.max));
  const KldSummary all = *SummarizeKld({inf});
  EXPECT_EQ(all.infinite, 1);
  EXPECT_EQ(all.mean_finite, 0.0);
}

TEST(EdgesByKindTest, CountsEachFactorByOriginAndCliquesAsPairs) {
  slam::PoseGraph graph;
  for (slam::NodeId id = 0; id < 4; ++id) graph.AddNode(id);
  slam::PoseEdge edge;
  edge.information = Eigen::Matrix3d::Identity();
  edge.from = 0, edge.to = 1, edge.kind = EdgeKind::kOdometry;
  graph.AddEdge(edge);
  edge.from = 1, edge.to = 2;
  graph.AddEdge(edge);
  edge.from = 0, edge.to = 2, edge.kind = EdgeKind::kLoop;
  graph.AddEdge(edge);
  slam::CliqueFactor clique;
  clique.nodes = {1, 2, 3};
  clique.T_root_node = {Pose2(), Pose2()};
  clique.information = Eigen::MatrixXd::Identity(6, 6);
  graph.AddClique(clique);
  EXPECT_EQ(EdgesByKind(graph), (std::map<std::string, std::int64_t>{
                                    {"odometry", 2}, {"loop", 1}, {"clique_pairs", 3}}));
}

// A map with no occupied cell has no distance to a wall: its blur is absent, never a 0.00 cm
// that reads as a perfect map.
TEST(SummaryJsonTest, BlurOfAMapWithoutOccupiedCellsIsAbsentNotZero) {
  RunSummary s;
  s.source = "x";
  ModeSummary m;
  m.blur = BlurSummary{std::nullopt, std::nullopt, 0.0, 0.0};
  s.modes["standard"] = m;
  const fs::path dir = FreshTempDir("json_empty_map");
  WriteSummaryJson((dir / "summary.json").string(), s);
  const auto j = nlohmann::json::parse(ReadFileText(dir / "summary.json"));
  EXPECT_EQ(Keys(j["modes"]["standard"]["blur"]), (std::set<std::string>{"thickness", "recall"}));
}

TEST(SummaryJsonTest, SeedAndDurationAbsentWhenUnknown) {
  RunSummary s;
  s.source = "intel.clf";
  const auto j = nlohmann::json::parse(SummaryJsonText(s));
  EXPECT_FALSE(j.contains("seed"));
  EXPECT_FALSE(j.contains("log_duration_s"));
  EXPECT_TRUE(j["modes"].is_object());
}

TEST(TimelineCsvTest, HeaderAndRows) {
  const fs::path p = FreshTempDir("csv") / "timeline.csv";
  WriteTimelineCsv(p.string(), Rows(3));
  EXPECT_FALSE(fs::exists(io::TempPathFor(p.string())));
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line,
            "obs,t_s,time_ms,nodes,edges,gamma,rss_mb,graph_bytes,loop_closures,optimize_ms,"
            "nodes_removed,match_ms,loop_ms,backend_ms,map_update_ms,gain_ms,marginalize_ms,"
            "sequential,odometry_lost");
  std::getline(in, line);
  EXPECT_EQ(line, "0,0.000000,1,10,20,0.25,100,1000,0,0,0,0,0,0,0,0,0,first,0");
  int more = 0;
  while (std::getline(in, line)) ++more;
  EXPECT_EQ(more, 2);
}

TEST(WriteFileTest, UnwritablePathThrows) {
  EXPECT_THROW(WriteTimelineCsv("/nonexistent_dir/x/timeline.csv", Rows(1)), std::runtime_error);
}

}  // namespace
}  // namespace lifelong::eval
