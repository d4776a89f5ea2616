#include "slam/pose_graph.hpp"

#include <gtest/gtest.h>

namespace lifelong::slam {
namespace {

PoseEdge Edge(NodeId from, NodeId to) {
  PoseEdge e;
  e.from = from;
  e.to = to;
  return e;
}

CliqueFactor Clique(std::vector<NodeId> nodes) {
  CliqueFactor c;
  const Eigen::Index k = static_cast<Eigen::Index>(nodes.size() - 1);
  c.T_root_node.assign(nodes.size() - 1, Pose2());
  c.information = Eigen::MatrixXd::Identity(3 * k, 3 * k);
  c.nodes = std::move(nodes);
  return c;
}

TEST(PoseGraph, AddNodesAndEdgesBuildsAdjacency) {
  PoseGraph g;
  for (NodeId id : {4, 1, 7}) g.AddNode(id);
  EXPECT_EQ(g.NodeIds(), (std::vector<NodeId>{1, 4, 7}));
  EXPECT_EQ(g.AddEdge(Edge(1, 4)), 0u);
  EXPECT_EQ(g.AddEdge(Edge(4, 7)), 1u);
  EXPECT_EQ(g.Neighbours(4), (std::set<NodeId>{1, 7}));
  EXPECT_EQ(g.Neighbours(1), (std::set<NodeId>{4}));
  EXPECT_EQ(g.EdgesOf(4), (std::vector<std::size_t>{0, 1}));
  EXPECT_THROW(g.AddNode(4), std::logic_error);
  EXPECT_THROW(g.AddEdge(Edge(1, 9)), std::logic_error);
  EXPECT_THROW(g.AddEdge(Edge(1, 1)), std::logic_error);
}

// 4 nodes, 2 edges + one clique over 3 nodes (3 pairs): e = 5, v(v-1)/2 = 6.
TEST(PoseGraph, GammaCountsCliquePairs) {
  PoseGraph g;
  EXPECT_EQ(g.Gamma(), 0.0);
  for (NodeId id = 0; id < 4; ++id) g.AddNode(id);
  g.AddEdge(Edge(0, 1));
  g.AddEdge(Edge(2, 3));
  EXPECT_DOUBLE_EQ(g.Gamma(), 2.0 / 6.0);
  g.AddClique(Clique({1, 2, 3}));
  EXPECT_EQ(g.NumEdgesForGamma(), 5u);
  EXPECT_DOUBLE_EQ(g.Gamma(), 5.0 / 6.0);
  EXPECT_EQ(g.Neighbours(1), (std::set<NodeId>{0, 2, 3}));
  EXPECT_EQ(g.CliquesOf(3), (std::vector<std::size_t>{0}));
  EXPECT_TRUE(g.CliquesOf(0).empty());
}

TEST(PoseGraph, RemoveNodeDropsItsFactorsAndAdjacency) {
  PoseGraph g;
  for (NodeId id = 0; id < 4; ++id) g.AddNode(id);
  g.AddEdge(Edge(0, 1));
  g.AddEdge(Edge(1, 2));
  g.AddEdge(Edge(2, 3));
  g.AddClique(Clique({0, 1, 3}));
  g.RemoveNode(1);
  EXPECT_FALSE(g.HasNode(1));
  EXPECT_EQ(g.NumNodes(), 3u);
  ASSERT_EQ(g.edges().size(), 1u);
  EXPECT_EQ(g.edges()[0].from, 2);
  EXPECT_TRUE(g.cliques().empty());
  EXPECT_TRUE(g.Neighbours(0).empty());  // 0 was tied only through 1 and the clique
  EXPECT_EQ(g.Neighbours(3), (std::set<NodeId>{2}));
  EXPECT_DOUBLE_EQ(g.Gamma(), 1.0 / 3.0);
  EXPECT_THROW(g.RemoveNode(1), std::logic_error);
  EXPECT_THROW(g.Neighbours(1), std::logic_error);
}

TEST(PoseGraph, RejectsInconsistentClique) {
  PoseGraph g;
  for (NodeId id = 0; id < 3; ++id) g.AddNode(id);
  CliqueFactor c = Clique({0, 1, 2});
  c.information = Eigen::MatrixXd::Identity(3, 3);
  EXPECT_THROW(g.AddClique(c), std::logic_error);
  EXPECT_THROW(g.AddClique(Clique({0, 9})), std::logic_error);
}

TEST(PoseGraph, BytesGrowWithFactors) {
  PoseGraph g;
  for (NodeId id = 0; id < 3; ++id) g.AddNode(id);
  const std::size_t before = g.Bytes();
  g.AddClique(Clique({0, 1, 2}));
  EXPECT_GE(g.Bytes(), before + 36 * sizeof(double));
}

}  // namespace
}  // namespace lifelong::slam
