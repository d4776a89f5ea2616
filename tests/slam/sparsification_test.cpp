// Sparsification with Chow-Liu trees: the Markov-blanket policy of a removal and the edge
// budget's sparsification without a removal (slam/marginal/marginalization.hpp).
#include <vector>

#include <gtest/gtest.h>

#include "slam/marginal/marginalization.hpp"
#include "tests/slam/marginalization_graphs.hpp"

namespace lifelong::slam {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using namespace test_util;  // tests/slam/marginalization_graphs.hpp

// Markov-blanket sparsification: with an extra edge a-b among the neighbours of k, the tree
// replaces it (m - 1 = 2 edges inside N), while the default policy keeps it beside the tree.
TEST(MarginalizeBlanket, TreeReplacesTheEdgesAmongTheNeighbours) {
  std::mt19937 rng(11);
  const Values v = RandomValues({0, 1, 2, 3}, &rng);
  PoseGraph g = Star(v, {1, 2, 3}, {{1, 2}}, &rng);
  const std::vector<NodeId> n{1, 2, 3};
  ASSERT_EQ(g.EdgesWithin(n).size(), 1u);

  PoseGraph kept = g;
  const auto plain = MarginalizeChowLiu(kept, v, 0);
  ApplyMarginalization(&kept, 0, plain);
  EXPECT_EQ(kept.EdgesWithin(n).size(), 3u);

  const auto blanket = MarginalizeChowLiu(g, v, 0, BlanketPolicy::kBlanket);
  EXPECT_TRUE(blanket.absorbed_blanket);
  EXPECT_GE(blanket.kl_divergence, 0.0);
  ApplyMarginalization(&g, 0, blanket);
  EXPECT_FALSE(g.HasNode(0));
  EXPECT_EQ(g.EdgesWithin(n).size(), 2u);
  EXPECT_EQ(g.edges().size(), 2u);

  // Exact marginalization takes no policy: the clique is the seed's fill-in.
  PoseGraph dense = Star(v, {1, 2, 3}, {}, &rng);
  EXPECT_FALSE(MarginalizeExact(dense, v, 0).absorbed_blanket);
}

// Sparsification without a removal (the pruning edge budget): the edges among a node and its
// neighbours become their Chow-Liu tree; edges leaving the set stay; a tree is left alone.
TEST(SparsifyWithin, ReplacesTheBlanketsEdgesByATreeAndLeavesTreesAlone) {
  std::mt19937 rng(5);
  const Values v = RandomValues({0, 1, 2, 3, 4, 9}, &rng);
  PoseGraph star = Star(v, {1, 2, 3, 4}, {}, &rng);
  const std::vector<NodeId> set{0, 1, 2, 3, 4};
  EXPECT_FALSE(SparsifyWithin(star, v, set).applied);

  PoseGraph g = Star(v, {1, 2, 3, 4}, {{1, 2}, {3, 4}, {2, 9}}, &rng);
  ASSERT_EQ(g.EdgesWithin(set).size(), 6u);
  const SparsificationResult r = SparsifyWithin(g, v, set);
  ASSERT_TRUE(r.applied);
  EXPECT_EQ(r.edges_before, 6u);
  ASSERT_EQ(r.edges.size(), 4u);
  // KL as an independent computation from the two edge sets.
  MatrixXd p = MatrixXd::Zero(15, 15), q = MatrixXd::Zero(15, 15);
  for (const PoseEdge& e : g.EdgesWithin(set)) AddEdgeHessian(e, v, set, &p);
  for (const PoseEdge& e : r.edges) AddEdgeHessian(e, v, set, &q);
  EXPECT_NEAR(r.kl_divergence, GaugeFixedKl(p, q), 1e-9);
  EXPECT_GT(r.kl_divergence, 0.0);  // the cycles carried information a tree cannot
  ApplySparsification(&g, r);
  EXPECT_EQ(g.EdgesWithin(set).size(), 4u);
  EXPECT_EQ(g.edges().size(), 5u);  // + the edge 2-9 leaving the set
  EXPECT_TRUE(g.Neighbours(9).count(2));
  for (const PoseEdge& e : r.edges) EXPECT_EQ(e.kind, EdgeKind::kMarginal);
}

// In a triangle whose edge 1-2 is a thousand times weaker than 0-1 and 0-2, the pair 1-2 is
// the least informative, so the tree keeps 0-1 and 0-2.
TEST(SparsifyWithin, DropsTheWeakestPairOfATriangle) {
  std::mt19937 rng(8);
  const Values v = RandomValues({0, 1, 2}, &rng);
  PoseGraph g;
  for (NodeId id : {0, 1, 2}) g.AddNode(id);
  g.AddEdge(ConsistentEdge(0, 1, v, 100.0 * Matrix3d::Identity()));
  g.AddEdge(ConsistentEdge(2, 0, v, 100.0 * Matrix3d::Identity()));
  g.AddEdge(ConsistentEdge(1, 2, v, 0.1 * Matrix3d::Identity()));
  const SparsificationResult r = SparsifyWithin(g, v, {0, 1, 2});
  ASSERT_TRUE(r.applied);
  ApplySparsification(&g, r);
  EXPECT_EQ(g.Neighbours(0), (std::set<NodeId>{1, 2}));
  EXPECT_EQ(g.Neighbours(1), (std::set<NodeId>{0}));
  EXPECT_LT(r.kl_divergence, 1e-2);
}

}  // namespace
}  // namespace lifelong::slam
