// The pruner on hand-made graphs: which node its policy picks, what a removal leaves in the
// graph and its records, and when the edge budget applies.
#include "slam/mapping/pruner.hpp"

#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include <gtest/gtest.h>

#include "slam/graph/dijkstra.hpp"
#include "test_graphs.hpp"

namespace lifelong::slam {
namespace {

const Eigen::Matrix3d kInfo = Eigen::Vector3d(100.0, 100.0, 400.0).asDiagonal();

// A ring of n nodes on a circle, each joined to the next, and every node to the one two
// ahead (a dense band: 2 edges per node).
void Ring(int n, PoseGraph* graph, Values* values) {
  *graph = test::Nodes(n);
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * test::kPi * i / n;
    (*values)[i] = Pose2(5.0 * std::cos(a), 5.0 * std::sin(a), a + test::kPi / 2.0);
  }
  for (int i = 0; i < n; ++i) {
    for (int step : {1, 2}) {
      const int j = (i + step) % n;
      graph->AddEdge(test::Edge(i, j, Between(values->at(i), values->at(j)), kInfo));
    }
  }
}

TEST(Pruner, ThePolicyPicksTheLowestGainUnderTheThreshold) {
  PruningConfig config;               // 5 bits
  config.mode = NamedMode("pruned");  // information-gain
  const Pruner pruner(config, OptimizerParams{});
  EXPECT_EQ(pruner.Next({{1, 7.0}, {2, 0.5}, {3, 2.0}}, 10), std::optional<NodeId>(2));
  EXPECT_FALSE(pruner.Next({{1, 7.0}, {3, 9.0}}, 10).has_value());
}

TEST(Pruner, ARemovalLeavesTheNeighboursConnectedAndIsRecorded) {
  PoseGraph graph;
  Values values;
  Ring(8, &graph, &values);
  PruningConfig config;
  config.mode = NamedMode("pruned");
  Pruner pruner(config, OptimizerParams{});
  const Replacement r = pruner.Marginalize(&graph, values, 3);
  EXPECT_EQ(r.neighbours, (std::vector<NodeId>{1, 2, 4, 5}));
  EXPECT_TRUE(graph.HasNode(3));  // Marginalize leaves the graph as it was
  pruner.Remove(&graph, 3, r, 1.25);
  EXPECT_FALSE(graph.HasNode(3));
  EXPECT_EQ(graph.NumNodes(), 7u);
  EXPECT_TRUE(IsConnected(graph));
  ASSERT_EQ(pruner.marginalizations().size(), 1u);
  EXPECT_EQ(pruner.marginalizations()[0].node, 3);
  EXPECT_EQ(pruner.marginalizations()[0].clique_size, 4u);
  EXPECT_DOUBLE_EQ(pruner.marginalizations()[0].information_gain_bits, 1.25);
}

TEST(Pruner, TheEdgeBudgetAppliesToTreeSparsifiersOnly) {
  PruningConfig config;
  config.max_edges_per_node = 1.5;
  const auto none = [] { return std::set<NodeId>{}; };

  PoseGraph graph;
  Values values;
  Ring(10, &graph, &values);  // 20 edges over 10 nodes
  config.mode = NamedMode("pruned");
  Pruner chow_liu(config, OptimizerParams{});
  chow_liu.KeepEdgeBudget(&graph, values, none);
  EXPECT_FALSE(chow_liu.sparsifications().empty());
  EXPECT_LT(graph.NumEdgesForGamma(), 20u);
  EXPECT_TRUE(IsConnected(graph));

  PoseGraph dense;
  Ring(10, &dense, &values);
  PruningConfig exact_config = config;
  exact_config.mode = NamedMode("pruned-exact");
  Pruner exact(exact_config, OptimizerParams{});
  exact.KeepEdgeBudget(&dense, values, none);
  EXPECT_TRUE(exact.sparsifications().empty());
  EXPECT_EQ(dense.NumEdgesForGamma(), 20u);

  // Nodes that are not settled are never sparsified.
  PoseGraph held;
  Ring(10, &held, &values);
  Pruner guarded(config, OptimizerParams{});
  guarded.KeepEdgeBudget(&held, values, [] {
    std::set<NodeId> all;
    for (NodeId i = 0; i < 10; ++i) all.insert(i);
    return all;
  });
  EXPECT_EQ(held.NumEdgesForGamma(), 20u);
}

TEST(Pruner, UnknownNamesAreRefused) {
  PruningConfig config;
  config.mode = {"oldest-first+chow-liu", "oldest-first", "chow-liu"};
  EXPECT_THROW(Pruner(config, OptimizerParams{}), std::invalid_argument);
  config.mode = {"information-gain+chow-lui", "information-gain", "chow-lui"};
  EXPECT_THROW(Pruner(config, OptimizerParams{}), std::invalid_argument);
}

}  // namespace
}  // namespace lifelong::slam
