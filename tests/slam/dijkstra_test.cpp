#include "slam/graph/dijkstra.hpp"

#include <gtest/gtest.h>

namespace lifelong::slam {
namespace {

PoseEdge Edge(NodeId a, NodeId b, const Pose2& z, double sigma_xy, double sigma_th) {
  PoseEdge e;
  e.from = a;
  e.to = b;
  e.T_from_to = z;
  e.information = Eigen::Vector3d(1.0 / (sigma_xy * sigma_xy), 1.0 / (sigma_xy * sigma_xy),
                                  1.0 / (sigma_th * sigma_th))
                      .asDiagonal();
  return e;
}

// Nodes 0..n-1 at x = 0, 1, 2, ... m, no edges yet.
void AddNodesAlongX(int n, PoseGraph* g, Values* v) {
  for (NodeId i = 0; i < n; ++i) {
    g->AddNode(i);
    (*v)[i] = Pose2(static_cast<double>(i), 0.0, 0.0);
  }
}

// Chain 0 -> 1 -> 2 along +x, 1 m apart. With only translational noise, covariances add:
// node 2 relative to node 0 has position variance 2 sigma^2 per axis.
TEST(ProjectCovariances, TranslationOnlyNoiseAddsUp) {
  PoseGraph g;
  Values v;
  AddNodesAlongX(3, &g, &v);
  g.AddEdge(Edge(0, 1, Pose2(1, 0, 0), 0.1, 1e-6));
  g.AddEdge(Edge(1, 2, Pose2(1, 0, 0), 0.1, 1e-6));
  const auto proj = ProjectCovariances(g, v, 0);
  ASSERT_EQ(proj.size(), 3u);
  EXPECT_NEAR(proj.at(2).covariance(0, 0), 0.02, 1e-6);
  EXPECT_NEAR(proj.at(2).covariance(1, 1), 0.02, 1e-6);
  EXPECT_EQ(proj.at(2).hops, 2);
  EXPECT_NEAR(proj.at(2).path_length_m, 2.0, 1e-12);
}

// A sparse GLC tree over {0, 1, 2} (glc.hpp): the marginal of y_1 as an edge 0 -> 1 and the
// conditional of y_2 given y_1 as a clique factor, singular on its own. Together they are
// definite, and the projection must reach node 2 through them with y_2's marginal
// covariance (factor by factor it saw ~1e9 m^2 and stopped there).
TEST(ProjectCovariances, PassesThroughASparseGlcTree) {
  PoseGraph g;
  Values v;
  AddNodesAlongX(3, &g, &v);
  g.AddEdge(Edge(0, 1, Pose2(1, 0, 0), 0.1, 0.01));  // Sigma_1 = diag(0.01, 0.01, 1e-4)
  CliqueFactor f;
  f.nodes = {0, 1, 2};
  f.T_root_node = {Pose2(1, 0, 0), Pose2(2, 0, 0)};
  Eigen::MatrixXd H(3, 6);
  H << -Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity();  // y_2 = y_1 + w
  const Eigen::Matrix3d omega = Eigen::Vector3d(100.0, 100.0, 1e4).asDiagonal();
  f.information = H.transpose() * omega * H;  // rank 3 of 6
  g.AddClique(f);
  ProjectionConfig config;
  config.max_position_sigma_m = 5.0;
  const auto proj = ProjectCovariances(g, v, 0, config);
  ASSERT_EQ(proj.count(2), 1u);
  // y_2's marginal: Sigma_1 + Omega^-1 = 0.01 + 0.01 per position axis.
  EXPECT_NEAR(proj.at(2).covariance(0, 0), 0.02, 1e-6);
  EXPECT_LT(proj.at(2).covariance(1, 1), 0.03);
}

// Heading noise at node 1 swings node 2 sideways by lever arm 1 m: var_y += sigma_th^2.
TEST(ProjectCovariances, HeadingNoiseGrowsLateralUncertainty) {
  PoseGraph g;
  Values v;
  AddNodesAlongX(3, &g, &v);
  g.AddEdge(Edge(0, 1, Pose2(1, 0, 0), 1e-6, 0.1));
  g.AddEdge(Edge(1, 2, Pose2(1, 0, 0), 1e-6, 1e-6));
  const auto proj = ProjectCovariances(g, v, 0);
  EXPECT_NEAR(proj.at(2).covariance(1, 1), 0.01, 1e-6);
  EXPECT_NEAR(proj.at(2).covariance(0, 0), 0.0, 1e-6);
}

TEST(ProjectCovariances, PrefersTheMoreCertainPath) {
  PoseGraph g;
  Values v;
  AddNodesAlongX(3, &g, &v);
  g.AddEdge(Edge(0, 1, Pose2(1, 0, 0), 0.5, 0.01));
  g.AddEdge(Edge(1, 2, Pose2(1, 0, 0), 0.5, 0.01));
  g.AddEdge(Edge(0, 2, Pose2(2, 0, 0), 0.05, 0.01));  // a tight loop closure
  const auto proj = ProjectCovariances(g, v, 0);
  EXPECT_EQ(proj.at(2).hops, 1);
  EXPECT_LT(proj.at(2).covariance(0, 0), 0.01);
}

TEST(ExpandByPathLength, StopsAtTheRadius) {
  PoseGraph g;
  Values v;
  for (NodeId i = 0; i < 5; ++i) {
    g.AddNode(i);
    v[i] = Pose2(static_cast<double>(i), 0.0, 0.0);
    if (i > 0) g.AddEdge(Edge(i - 1, i, Pose2(1, 0, 0), 0.1, 0.1));
  }
  const auto near = ExpandByPathLength(g, v, 2, 1.5);
  EXPECT_EQ(near.size(), 3u);
  EXPECT_TRUE(near.count(1) && near.count(2) && near.count(3));
  EXPECT_TRUE(IsConnected(g));
  g.RemoveNode(2);
  EXPECT_FALSE(IsConnected(g));
}

}  // namespace
}  // namespace lifelong::slam
