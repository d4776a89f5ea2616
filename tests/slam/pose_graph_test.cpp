#include "slam/graph/pose_graph.hpp"

#include <algorithm>

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

// The plain factors io reads and writes (types/pose_factors.hpp) make the same graph back.
TEST(PoseGraph, FactorsRoundTripKeepsNodesEdgesAndCliquesInOrder) {
  PoseFactors factors;
  factors.nodes = {7, 1, 4, 9};
  factors.edges = {Edge(4, 7), Edge(1, 4), Edge(7, 9)};
  factors.cliques = {Clique({9, 1, 4})};
  const PoseGraph g = PoseGraph::FromFactors(factors);
  EXPECT_EQ(g.NodeIds(), (std::vector<NodeId>{1, 4, 7, 9}));
  EXPECT_EQ(g.Neighbours(9), (std::set<NodeId>{1, 4, 7}));
  const PoseFactors back = g.Factors();
  EXPECT_EQ(back.nodes, (std::vector<NodeId>{1, 4, 7, 9}));  // ascending, as written
  ASSERT_EQ(back.edges.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back.edges[i].from, factors.edges[i].from);
    EXPECT_EQ(back.edges[i].to, factors.edges[i].to);
  }
  ASSERT_EQ(back.cliques.size(), 1u);
  EXPECT_EQ(back.cliques[0].nodes, (std::vector<NodeId>{9, 1, 4}));
  factors.edges.push_back(Edge(4, 5));  // a node the factors do not list
  EXPECT_THROW(PoseGraph::FromFactors(factors), std::logic_error);
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

// Adjacency is kept by counting the factors that join each pair; after any sequence of
// removals it must equal the adjacency rebuilt from the factors that remain (a pair joined
// by an edge and a clique stays joined while either remains).
TEST(PoseGraph, AdjacencyStaysEqualToTheFactorsThroughRemovals) {
  PoseGraph g;
  for (NodeId id = 0; id < 12; ++id) g.AddNode(id);
  for (NodeId id = 0; id + 1 < 12; ++id) g.AddEdge(Edge(id, id + 1));
  g.AddEdge(Edge(0, 5));
  g.AddEdge(Edge(0, 5));  // a duplicate pair
  g.AddEdge(Edge(3, 9));
  g.AddClique(Clique({2, 3, 7}));
  g.AddClique(Clique({3, 7, 10, 11}));
  const auto rebuilt = [&g](NodeId id) {
    std::set<NodeId> out;
    for (const PoseEdge& e : g.edges()) {
      if (e.from == id) out.insert(e.to);
      if (e.to == id) out.insert(e.from);
    }
    for (const CliqueFactor& c : g.cliques()) {
      if (std::find(c.nodes.begin(), c.nodes.end(), id) == c.nodes.end()) continue;
      for (NodeId n : c.nodes) {
        if (n != id) out.insert(n);
      }
    }
    return out;
  };
  const auto check = [&] {
    for (NodeId id : g.NodeIds()) EXPECT_EQ(g.Neighbours(id), rebuilt(id)) << "node " << id;
  };
  check();
  g.RemoveEdgesWithin({0, 5});  // both duplicates go
  EXPECT_FALSE(g.Neighbours(0).count(5));
  check();
  g.RemoveEdgesWithin({3, 7});  // no edge there: 3-7 stays joined by the cliques
  EXPECT_TRUE(g.Neighbours(3).count(7));
  g.RemoveCliquesWithin({2, 3, 7});
  EXPECT_TRUE(g.Neighbours(3).count(7));  // still in {3, 7, 10, 11}
  check();
  for (NodeId id : {4, 10, 3, 8}) {
    g.RemoveNode(id);
    check();
  }
  std::vector<NodeId> from;  // 0-1 1-2 5-6 6-7, in the order they were added
  for (const PoseEdge& e : g.edges()) from.push_back(e.from);
  EXPECT_EQ(from, (std::vector<NodeId>{0, 1, 5, 6}));
  EXPECT_TRUE(g.cliques().empty());
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
