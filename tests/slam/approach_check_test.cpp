// The approach test of a loop-closure match (slam/loops/approach_check.hpp): in a corridor
// whose walls look alike everywhere, the pillar the robot passed on its way in tells the true
// place from one 2 m along.
#include "slam/loops/approach_check.hpp"

#include <vector>

#include <gtest/gtest.h>

#include "synthetic_scans.hpp"

namespace lifelong::slam {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A corridor along x (walls at y = 0 and 2, 40 m) with a pillar at x 5-6 against its south
// wall. Nodes 0..29 drive it east at y = 1 from x = 1 (travelled 0..29 m); nodes 30..43 drive
// it again from x = 1 (travelled 100..113 m): node 43 is at x = 14, the pillar 8-9 m behind.
struct Corridor {
  PoseGraph graph;
  Values values;
  NodeStore nodes;
  std::vector<NodeId> recent;

  Corridor() {
    testing::World w = {{0.0, 0.0, 40.0, 0.0}, {0.0, 2.0, 40.0, 2.0}};
    testing::AddRectangle(5.0, 0.0, 6.0, 0.5, &w);
    Add(w, 0, 30, 0.0);
    Add(w, 30, 14, 100.0);
  }
  void Add(const testing::World& w, int first, int count, double travelled) {
    for (int k = 0; k < count; ++k) {
      const NodeId id = first + k;
      const Pose2 X(1.0 + k, 1.0, 0.0);
      graph.AddNode(id);
      NodeData data;
      data.scan = testing::SimulateScan(w, X, 361, 2.0 * kPi * 360.0 / 361.0, 12.0);
      data.points = ScanToPoints(data.scan, 0.05);
      data.travelled_m = travelled + k;
      nodes.emplace(id, std::move(data));
      values[id] = X;
      recent.push_back(id);
    }
  }
  LoopClosingView View() const { return {graph, values, nodes, recent}; }
};

LoopClosingConfig Config() {
  LoopClosingConfig lc;
  lc.matcher.resolution_m = 0.05;
  lc.matcher.sigma_m = 0.08;
  lc.context_span_m = 9.0;
  return lc;
}

TEST(ApproachCheck, TheWayInTellsTheTruePlaceFromALookAlikeOne) {
  const Corridor c;
  ReferenceGrid grid;
  NodeReach reach;
  const Pose2 truth(14.0, 1.0, 0.0), along(16.0, 1.0, 0.0);
  // Node 43's own scan sees two walls (and, 8 m back, the pillar): only the approach's
  // pillar, placed by the chain behind it, says which of the two is right.
  EXPECT_TRUE(ApproachAgrees(c.View(), 43, truth, along, Config(), &reach, &grid));
  EXPECT_FALSE(ApproachAgrees(c.View(), 43, along, truth, Config(), &reach, &grid));
}

TEST(ApproachCheck, NoApproachOrNoOlderScansJudgeNothing) {
  const Corridor c;
  ReferenceGrid grid;
  NodeReach reach;
  const Pose2 truth(14.0, 1.0, 0.0), along(16.0, 1.0, 0.0);
  LoopClosingConfig lc = Config();
  lc.context_span_m = 0.5;  // no node in the last half metre but the current one
  EXPECT_TRUE(ApproachAgrees(c.View(), 43, along, truth, lc, &reach, &grid));
  lc = Config();
  lc.min_path_separation_m = 200.0;  // every node is too recent to count as older
  EXPECT_TRUE(ApproachAgrees(c.View(), 43, along, truth, lc, &reach, &grid));
}

}  // namespace
}  // namespace lifelong::slam
