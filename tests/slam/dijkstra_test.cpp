#include "slam/graph/dijkstra.hpp"

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/LU>

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

// A GLC-style conditional over {r, p, c} with nodes 1 m apart along x: information on
// y_c - a y_p only (rank 3 of 6), with the given precisions.
CliqueFactor Conditional(NodeId r, NodeId p, NodeId c, const Eigen::Matrix3d& a,
                         const Eigen::Vector3d& precision) {
  CliqueFactor f;
  f.nodes = {r, p, c};
  f.T_root_node = {Pose2(static_cast<double>(p - r), 0, 0),
                   Pose2(static_cast<double>(c - r), 0, 0)};
  Eigen::MatrixXd H(3, 6);
  H << -a, Eigen::Matrix3d::Identity();
  f.information = H.transpose() * precision.asDiagonal() * H;
  return f;
}

// The central-difference Jacobian (rows x cols) of f at 0.
template <typename F>
Eigen::MatrixXd NumericJacobian(F&& f, int rows, int cols) {
  Eigen::MatrixXd J(rows, cols);
  for (int k = 0; k < cols; ++k) {
    Eigen::VectorXd plus = Eigen::VectorXd::Zero(cols), minus = plus;
    plus(k) = 1e-6;
    minus(k) = -1e-6;
    J.col(k) = (f(plus) - f(minus)) / 2e-6;
  }
  return J;
}

// A covariance of a pose's frame turned into the world's (x, y rotated by theta).
Eigen::Matrix3d RotateXy(const Eigen::Matrix3d& c, double theta) {
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  r.topLeftCorner<2, 2>() << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  return r * c * r.transpose();
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
  // y_2 = y_1 + w, rank 3 of 6.
  g.AddClique(Conditional(0, 1, 2, Eigen::Matrix3d::Identity(), {100.0, 100.0, 1e4}));
  ProjectionConfig config;
  config.max_position_sigma_m = 5.0;
  const auto proj = ProjectCovariances(g, v, 0, config);
  ASSERT_EQ(proj.count(2), 1u);
  // y_2's marginal: Sigma_1 + Omega^-1 = 0.01 + 0.01 per position axis.
  EXPECT_NEAR(proj.at(2).covariance(0, 0), 0.02, 1e-6);
  EXPECT_LT(proj.at(2).covariance(1, 1), 0.03);
}

// A GLC conditional whose tree marginal went to another group: the clique {0, 1, 2} alone says
// where 2 is relative to 1 (y_2 given y_1) but not where either is relative to its root 0.
// Node 1 is tied to the rest by an edge 4 -> 1 and node 2 to the current node 3. The
// projection from 3 must pass from 2 to 1 along what the clique does say (before the fix,
// members were linked by Sigma_11 + Sigma_22, ~1e9 m^2 here, and it stopped at 2).
TEST(ProjectCovariances, PassesBetweenMembersOfAGroupSingularAlone) {
  PoseGraph g;
  Values v;
  AddNodesAlongX(5, &g, &v);
  g.AddEdge(Edge(2, 3, Pose2(1, 0, 0), 0.1, 1e-3));
  g.AddEdge(Edge(4, 1, Pose2(-3, 0, 0), 0.1, 1e-3));
  // d_12 = y_2 - Ad(Z_12^-1) y_1 with Z_12 = (1, 0, 0): Ad = [I, (0, 1)^T; 0 1].
  Eigen::Matrix3d ad = Eigen::Matrix3d::Identity();
  ad(1, 2) = 1.0;
  g.AddClique(Conditional(0, 1, 2, ad, {100.0, 100.0, 1e6}));
  ProjectionConfig config;
  config.max_position_sigma_m = 5.0;
  const auto proj = ProjectCovariances(g, v, 3, config);
  ASSERT_EQ(proj.count(1), 1u);
  EXPECT_EQ(proj.count(4), 1u);
  EXPECT_EQ(proj.count(0), 0u);  // nothing ties the root to the others
  // 3 -> 2 -> 1: 0.01 + 0.01 along x; across, the headings (1e-6) swing it by under 1e-5.
  EXPECT_NEAR(proj.at(1).covariance(0, 0), 0.02, 1e-5);
  EXPECT_NEAR(proj.at(1).covariance(1, 1), 0.02, 1e-4);
}

// A dense clique that is the exact marginal of a chain 0 -> 1 -> 2 (relative to root 0):
// the link it gives from 1 to 2 is the edge 1 -> 2 itself (y_1 and y_2 are correlated
// through the edge 0 -> 1, and y_2 sees it through the lever arm of Z_12), in both
// directions. The joint covariance of y comes from numeric Jacobians, not from the adjoint.
TEST(ProjectCovariances, ADenseMarginalLinksItsMembersAsTheChainDid) {
  const Pose2 X0(0.0, 0.0, 0.0), X1(1.0, 0.2, 0.5), X2(1.6, 1.1, 1.2);
  const Pose2 Z1 = Between(X0, X1), Z2 = Between(X0, X2), Z12 = Between(X1, X2);
  const Eigen::Matrix3d C01 = Eigen::Vector3d(0.01, 0.02, 0.003).asDiagonal();
  const Eigen::Matrix3d C12 = Eigen::Vector3d(0.02, 0.01, 0.002).asDiagonal();
  const auto t2v = [](const Pose2& p) { return Eigen::Vector3d(p.x, p.y, p.theta); };
  const auto v2t = [](const Eigen::VectorXd& e, int at) {
    return Pose2(e(at), e(at + 1), e(at + 2));
  };
  // y(e) with e = (e01, e12), the chain's edge errors; and the reverse error of 2 -> 1.
  const auto y = [&](const Eigen::VectorXd& e) {
    Eigen::VectorXd out(6);
    out << e.head<3>(), t2v(Z2.Inverse() * Z1 * v2t(e, 0) * Z12 * v2t(e, 3));
    return out;
  };
  const auto back = [&](const Eigen::VectorXd& e) {
    return Eigen::VectorXd(t2v(Z12 * (Z12 * v2t(e, 3)).Inverse()));
  };
  const Eigen::MatrixXd J = NumericJacobian(y, 6, 6), Jb = NumericJacobian(back, 3, 6);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(6, 6);
  C.topLeftCorner<3, 3>() = C01;
  C.bottomRightCorner<3, 3>() = C12;
  PoseGraph g;
  Values v{{0, X0}, {1, X1}, {2, X2}};
  for (NodeId i = 0; i < 3; ++i) g.AddNode(i);
  CliqueFactor f;
  f.nodes = {0, 1, 2};
  f.T_root_node = {Z1, Z2};
  f.information = (J * C * J.transpose()).inverse();
  g.AddClique(f);
  const auto ahead = ProjectCovariances(g, v, 1);
  EXPECT_TRUE(ahead.at(2).covariance.isApprox(RotateXy(C12, X2.theta), 1e-6))
      << ahead.at(2).covariance;
  const Eigen::Matrix3d C21 = Jb * C * Jb.transpose();
  const auto behind = ProjectCovariances(g, v, 2);
  EXPECT_TRUE(behind.at(1).covariance.isApprox(RotateXy(C21, X1.theta), 1e-6))
      << behind.at(1).covariance;
}

// A member's link back to the root carries its heading's lever arm: the error of j -> r is
// -Ad(Z_j) y_j in r's frame. A clique {0, 1} 4 m apart with y_1's covariance C; from node 1
// the root's covariance is that of the reverse error, from a numeric Jacobian.
TEST(ProjectCovariances, ALinkBackToTheRootCarriesTheLeverArm) {
  const Pose2 X0(0.0, 0.0, 0.3), X1(3.0, 2.5, 1.0);
  const Pose2 Z = Between(X0, X1);
  const Eigen::Matrix3d C = Eigen::Vector3d(0.01, 0.02, 0.004).asDiagonal();
  const auto back = [&](const Eigen::VectorXd& e) {
    const Pose2 r = Z * (Z * Pose2(e.x(), e.y(), e.z())).Inverse();
    return Eigen::VectorXd(Eigen::Vector3d(r.x, r.y, r.theta));
  };
  const Eigen::Matrix3d J = NumericJacobian(back, 3, 3);
  PoseGraph g;
  Values v{{0, X0}, {1, X1}};
  g.AddNode(0);
  g.AddNode(1);
  CliqueFactor f;
  f.nodes = {0, 1};
  f.T_root_node = {Z};
  f.information = C.inverse();
  g.AddClique(f);
  const Eigen::Matrix3d expected = RotateXy(J * C * J.transpose(), X0.theta);
  const auto proj = ProjectCovariances(g, v, 1);
  EXPECT_TRUE(proj.at(0).covariance.isApprox(expected, 1e-6)) << proj.at(0).covariance;
}

// The group cache gives what a projection without it gives, to the bit, also after the
// group's factor changed, and it drops the groups that left the graph.
TEST(ProjectCovariances, TheGroupCacheChangesNothing) {
  PoseGraph g;
  Values v;
  AddNodesAlongX(4, &g, &v);
  g.AddEdge(Edge(0, 1, Pose2(1, 0, 0), 0.1, 0.01));
  g.AddEdge(Edge(2, 3, Pose2(1, 0, 0), 0.1, 0.01));
  CliqueFactor f = Conditional(1, 2, 3, Eigen::Matrix3d::Identity(), {100.0, 100.0, 1e4});
  g.AddClique(f);
  CliqueGroupCache cache;
  const auto same = [&](NodeId source) {
    const auto with = ProjectCovariances(g, v, source, {}, &cache);
    const auto without = ProjectCovariances(g, v, source);
    ASSERT_EQ(with.size(), without.size());
    for (const auto& [id, node] : without) {
      EXPECT_TRUE(with.at(id).covariance == node.covariance) << "node " << id;
    }
  };
  same(0);
  same(3);
  EXPECT_EQ(cache.size(), 1u);
  // The factor changes in place (a later removal replaced it): the entry is recomputed.
  g.RemoveCliquesWithin({1, 2, 3});
  f.information *= 4.0;
  g.AddClique(f);
  same(0);
  // Its root leaves the graph's cliques: the entry goes.
  g.RemoveCliquesWithin({1, 2, 3});
  same(0);
  EXPECT_EQ(cache.size(), 0u);
}

// A GLC conditional of y_2 given y_1 (relative to root 0) whose regression is not the
// adjoint (A = I/2: node 2 also leans on the root), and whose tree marginal, the link 0 -> 1,
// lies in the group rooted at 5 (a clique over {5, 0, 1}, y_0 and y_1 independent). Alone,
// group 0 leaves y_1 free, and (A - Ad) carries that into every link it gives: the projection
// from 3 (tied to 2 by an edge) stopped at 2 before group 0 was anchored by group 5's link.
TEST(ProjectCovariances, AGroupTakesItsMissingMarginalFromAnother) {
  PoseGraph g;
  Values v;
  AddNodesAlongX(6, &g, &v);
  g.AddEdge(Edge(2, 3, Pose2(1, 0, 0), 0.1, 1e-3));  // 0.01 per axis
  g.AddClique(Conditional(0, 1, 2, 0.5 * Eigen::Matrix3d::Identity(), {100.0, 100.0, 1e6}));
  CliqueFactor marginal;  // y_0, y_1 relative to 5: 0.02 per position axis each
  marginal.nodes = {5, 0, 1};
  marginal.T_root_node = {Pose2(-5, 0, 0), Pose2(-4, 0, 0)};
  marginal.information =
      Eigen::VectorXd((Eigen::VectorXd(6) << 50.0, 50.0, 1e7, 50.0, 50.0, 1e7).finished())
          .asDiagonal();
  g.AddClique(marginal);
  ProjectionConfig config;
  config.max_position_sigma_m = 5.0;
  const auto proj = ProjectCovariances(g, v, 3, config);
  ASSERT_EQ(proj.count(0), 1u);
  ASSERT_EQ(proj.count(1), 1u);
  EXPECT_EQ(proj.count(5), 1u);
  // Anchored, Sigma_11 = 0.04 (group 5's link 0 -> 1), Sigma_22 = A Sigma_11 A^T + 0.01 =
  // 0.02: node 0 is 3 -> 2 -> 0, 0.01 + 0.02; node 1 is 3 -> 2 -> 1, 0.01 + the variance of
  // y_1 - y_2 = y_1 / 2 - w, 0.01 + 0.01 (the headings add under 1e-4).
  EXPECT_NEAR(proj.at(0).covariance(0, 0), 0.03, 1e-4);
  EXPECT_NEAR(proj.at(1).covariance(0, 0), 0.03, 1e-4);
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
