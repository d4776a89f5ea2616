#include "slam/sparsify/set_marginal.hpp"

#include <algorithm>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/LU>

#include "slam/marginal/marginalization.hpp"
#include "slam/sparsify/offline_sparsify.hpp"
#include "slam/sparsify/sparsifier.hpp"
#include "tests/slam/marginalization_graphs.hpp"

namespace lifelong::slam {
namespace {

using namespace test_util;  // tests/slam/marginalization_graphs.hpp
using Eigen::MatrixXd;
using Eigen::VectorXd;

/// Nodes 0..n-1 in a chain with loop edges every few nodes; measurements off the estimate, so
/// the gradient is not zero.
PoseGraph Loopy(int n, const Values& v, std::mt19937* rng) {
  PoseGraph g;
  for (const auto& [id, pose] : v) g.AddNode(id);
  std::normal_distribution<double> noise(0.0, 0.05);
  const auto add = [&](NodeId a, NodeId b) {
    PoseEdge e = ConsistentEdge(a, b, v, RandomInfo(rng));
    e.T_from_to = e.T_from_to * Pose2(noise(*rng), noise(*rng), noise(*rng));
    g.AddEdge(e);
  };
  for (NodeId i = 0; i + 1 < n; ++i) add(i, i + 1);
  for (NodeId i = 0; i + 5 < n; i += 3) add(i, i + 5);
  return g;
}

/// H and g of every factor of `graph` over its nodes (ascending), dense.
LocalSystem Linearized(const PoseGraph& graph, const Values& values) {
  const std::vector<NodeId> nodes = graph.NodeIds();
  LocalSystem s = LinearizeEdges(nodes, values, graph.edges());
  for (const CliqueFactor& c : graph.cliques()) AddCliqueLinearized(c, values, nodes, &s.H, &s.g);
  return s;
}

TEST(SetMarginal, ConnectedSetsFollowTheFactorsAmongTheRemovedNodes) {
  std::mt19937 rng(1);
  const Values v = RandomValues({0, 1, 2, 3, 4, 5, 6, 7, 8, 9}, &rng);
  const PoseGraph g = Loopy(10, v, &rng);  // loops 0-5, 3-8
  const auto sets = ConnectedSets(g, {1, 2, 4, 7, 8, 9});
  ASSERT_EQ(sets.size(), 3u);
  EXPECT_EQ(sets[0], (std::vector<NodeId>{1, 2}));
  EXPECT_EQ(sets[1], (std::vector<NodeId>{4}));
  EXPECT_EQ(sets[2], (std::vector<NodeId>{7, 8, 9}));
}

TEST(SetMarginal, EqualsTheDenseSchurComplement) {
  std::mt19937 rng(2);
  const Values v = RandomValues({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}, &rng);
  const PoseGraph g = Loopy(12, v, &rng);
  const std::vector<NodeId> set{3, 4, 5, 6, 7};
  const std::optional<SetMarginal> m = MarginalizeSet(g, v, set, false);
  ASSERT_TRUE(m.has_value());
  ASSERT_EQ(m->boundary, (std::vector<NodeId>{0, 2, 8, 11}));  // loops 0-5, 3-8, 6-11
  // Dense: the factors touching the set over [set, boundary], then H_BB - H_BS H_SS^-1 H_SB.
  std::vector<NodeId> index = set;
  index.insert(index.end(), m->boundary.begin(), m->boundary.end());
  std::vector<PoseEdge> touching;
  for (const PoseEdge& e : g.edges()) {
    const auto in = [&](NodeId n) { return std::binary_search(set.begin(), set.end(), n); };
    if (in(e.from) || in(e.to)) touching.push_back(e);
  }
  const LocalSystem s = LinearizeEdges(index, v, touching);
  const Eigen::Index ns = 15, nb = 12;
  const MatrixXd hss_inv = s.H.topLeftCorner(ns, ns).inverse();
  const MatrixXd lambda = s.H.bottomRightCorner(nb, nb) -
                          s.H.bottomLeftCorner(nb, ns) * hss_inv * s.H.topRightCorner(ns, nb);
  const VectorXd g_b = s.g.tail(nb) - s.H.bottomLeftCorner(nb, ns) * hss_inv * s.g.head(ns);
  EXPECT_LT((m->marginal.lambda_N - lambda).norm(), 1e-9 * lambda.norm());
  EXPECT_LT((m->marginal.g_N - g_b).norm(), 1e-9 * (1.0 + g_b.norm()));
}

TEST(SetMarginal, SetBySetEqualsOneAtATimeForTheExactMethods) {
  std::mt19937 rng(3);
  std::vector<NodeId> ids;
  for (NodeId i = 0; i < 30; ++i) ids.push_back(i);
  const Values v = RandomValues(ids, &rng);
  const PoseGraph full = Loopy(30, v, &rng);
  const std::vector<NodeId> remove = RemovalForKeepShare(ids, 0.3);
  SparsifierConfig config;
  config.means = FactorMeans::kGradient;
  for (const char* name : {"exact", "glc-dense"}) {
    const auto by_sets = MakeSparsifier(name, config);
    ASSERT_TRUE(by_sets->ReplacesSets()) << name;
    PoseGraph batch = full;
    SparsifyOffline(&batch, v, remove, *by_sets);
    PoseGraph sequential = full;
    for (NodeId k : remove) ApplyReplacement(&sequential, k, by_sets->Replace(sequential, v, k));
    ASSERT_EQ(batch.NodeIds(), sequential.NodeIds()) << name;
    const LocalSystem a = Linearized(batch, v), b = Linearized(sequential, v);
    EXPECT_LT((a.H - b.H).norm(), 1e-8 * b.H.norm()) << name;
    EXPECT_LT((a.g - b.g).norm(), 1e-8 * (1.0 + b.g.norm())) << name;
    EXPECT_GT(b.g.norm(), 1e-3) << name;  // the gradient was kept, and is not trivially 0
  }
}

TEST(SetMarginal, ASetWithOneBoundaryNodeFallsBackToOneAtATime) {
  std::mt19937 rng(4);
  const Values v = RandomValues({0, 1, 2, 3, 4, 5}, &rng);
  PoseGraph g;
  for (const auto& [id, pose] : v) g.AddNode(id);
  for (NodeId i = 0; i < 5; ++i) g.AddEdge(ConsistentEdge(i, i + 1, v, RandomInfo(&rng)));
  EXPECT_FALSE(MarginalizeSet(g, v, {4, 5}, false).has_value());  // a dangling end
  SparsifyOffline(&g, v, {4, 5}, *MakeSparsifier("exact"));
  EXPECT_EQ(g.NodeIds(), (std::vector<NodeId>{0, 1, 2, 3}));
  EXPECT_EQ(g.edges().size(), 3u);
}

}  // namespace
}  // namespace lifelong::slam
