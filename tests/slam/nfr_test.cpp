// Nonlinear factor recovery (slam/sparsify/nfr.hpp): the tree's closed form, the subgraph's
// projected Newton solver and the two sparsifiers against chow-liu.
#include "slam/sparsify/nfr.hpp"

#include <cmath>
#include <random>
#include <set>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "slam/graph/se2.hpp"
#include "slam/marginal/marginalization.hpp"
#include "slam/sparsify/sparsifier.hpp"
#include "tests/slam/marginalization_graphs.hpp"

namespace lifelong::slam {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using namespace test_util;  // tests/slam/marginalization_graphs.hpp

std::set<std::pair<NodeId, NodeId>> Pairs(const std::vector<PoseEdge>& edges) {
  std::set<std::pair<NodeId, NodeId>> pairs;
  for (const PoseEdge& e : edges) pairs.insert({std::min(e.from, e.to), std::max(e.from, e.to)});
  return pairs;
}

TEST(Nfr, TreeIsExactWhenTheMarginalIsATree) {
  // As in marginalization_test: 1, 2, 3 and k = 4 share one dense clique factor encoding the
  // tree 1-2, 2-3, 1-4; removing the leaf 4 leaves the tree 1-2-3, which NFR must recover.
  std::mt19937 rng(21);
  const Values v = RandomValues({1, 2, 3, 4}, &rng);
  const std::vector<NodeId> all{1, 2, 3, 4};
  MatrixXd h = MatrixXd::Zero(12, 12);
  AddEdgeHessian(ConsistentEdge(1, 2, v, RandomInfo(&rng)), v, all, &h);
  AddEdgeHessian(ConsistentEdge(2, 3, v, RandomInfo(&rng)), v, all, &h);
  AddEdgeHessian(ConsistentEdge(1, 4, v, RandomInfo(&rng)), v, all, &h);
  PoseGraph g;
  for (NodeId id : all) g.AddNode(id);
  g.AddClique(ToCliqueFactor(all, v, h));
  for (const char* name : {"nfr-tree", "nfr-subgraph"}) {
    const Replacement r = MakeSparsifier(name)->Replace(g, v, 4);
    EXPECT_NEAR(r.kl_divergence, 0.0, 1e-9) << name;
    EXPECT_EQ(Pairs(r.edges), (std::set<std::pair<NodeId, NodeId>>{{1, 2}, {2, 3}})) << name;
    EXPECT_FALSE(r.regularized);
  }
  // The recovered edges carry the whole marginal: their Hessian is Lambda_N.
  const Replacement r = MakeSparsifier("nfr-tree")->Replace(g, v, 4);
  MatrixXd lambda_q = MatrixXd::Zero(9, 9);
  for (const PoseEdge& e : r.edges) AddEdgeHessian(e, v, {1, 2, 3}, &lambda_q);
  const MatrixXd lambda_N = SchurComplementFirstBlock(LinearizeAround(g, v, 4).H);
  EXPECT_TRUE(lambda_q.isApprox(lambda_N, 1e-9));
}

TEST(Nfr, SubgraphIsNeverWorseThanTheTreeWhichEqualsChowLiu) {
  // On the same tree NFR's closed form and chow-liu's exact conditionals coincide (nfr.hpp
  // step 4): chow-liu's edges are KL-optimal for its topology, so nfr-tree can only tie. The
  // subgraph adds the pairs joined before the removal and must lower the KL strictly.
  std::mt19937 rng(33);
  int with_extra = 0;
  const int trials = 12;
  for (int trial = 0; trial < trials; ++trial) {
    const Values v = RandomValues({0, 1, 2, 3, 4, 5, 6}, &rng);
    PoseGraph g = Star(v, {1, 2, 3, 4, 5, 6}, {}, &rng);
    // Weak edges among N (loop closures of a tenth of the spokes' information): the tree
    // takes strong pairs, so these stay candidates for the subgraph.
    for (const auto& [a, b] : {std::pair<NodeId, NodeId>{1, 3}, {2, 5}, {4, 6}, {3, 6}}) {
      g.AddEdge(ConsistentEdge(a, b, v, 0.1 * RandomInfo(&rng)));
    }
    const Replacement cl = MakeSparsifier("chow-liu")->Replace(g, v, 0);
    const Replacement tree = MakeSparsifier("nfr-tree")->Replace(g, v, 0);
    const Replacement sub = MakeSparsifier("nfr-subgraph")->Replace(g, v, 0);
    ASSERT_TRUE(std::isfinite(cl.kl_divergence));
    EXPECT_GT(tree.kl_divergence, 1e-6) << "a loopy marginal: the tree loses something";
    EXPECT_NEAR(tree.kl_divergence, cl.kl_divergence, 1e-9 * (1.0 + cl.kl_divergence))
        << "trial " << trial;
    EXPECT_EQ(Pairs(tree.edges), Pairs(cl.edges));
    EXPECT_EQ(tree.edges.size(), 5u);
    EXPECT_LE(sub.kl_divergence, tree.kl_divergence + 1e-9) << "trial " << trial;
    EXPECT_LE(sub.edges.size(), 2u * 5u);  // budget: m - 1 extra edges
    for (const auto& pair : Pairs(tree.edges)) EXPECT_EQ(Pairs(sub.edges).count(pair), 1u);
    if (sub.edges.size() > tree.edges.size()) {  // an extra edge that carries something
      ++with_extra;
      EXPECT_LT(sub.kl_divergence, tree.kl_divergence - 1e-6) << "trial " << trial;
    }
  }
  EXPECT_GE(with_extra, trials / 2);
}

TEST(Nfr, ChordRatioBoundsTheExtraEdges) {
  std::mt19937 rng(5);
  const Values v = RandomValues({0, 1, 2, 3, 4, 5}, &rng);
  std::vector<std::pair<NodeId, NodeId>> all;  // every pair of neighbours joined
  for (NodeId a = 1; a <= 5; ++a) {
    for (NodeId b = a + 1; b <= 5; ++b) all.emplace_back(a, b);
  }
  const PoseGraph g = Star(v, {1, 2, 3, 4, 5}, all, &rng);
  const Replacement tree = MakeSparsifier("nfr-tree")->Replace(g, v, 0);
  double previous = tree.kl_divergence;
  for (double ratio : {0.0, 0.5, 1.0, 1.5}) {
    SparsifierConfig config;
    config.nfr_chord_ratio = ratio;
    const Replacement r = MakeSparsifier("nfr-subgraph", config)->Replace(g, v, 0);
    EXPECT_EQ(r.edges.size(), 4u + static_cast<std::size_t>(std::floor(ratio * 4))) << ratio;
    EXPECT_LE(r.kl_divergence, previous + 1e-9) << ratio;  // more edges never lose
    previous = r.kl_divergence;
  }
  EXPECT_LT(previous, tree.kl_divergence - 1e-6);  // all 10 pairs: strictly better
}

/// Sigma and Jacobians of k = 0's clique in a star with `extra` edges among neighbours, on
/// the topology `pairs` (indices into the neighbours; the gauge holds index 0).
struct SmallProblem {
  MatrixXd sigma;
  std::vector<NfrJacobian> jacobians;
};
SmallProblem MakeProblem(std::mt19937* rng, const std::vector<std::pair<int, int>>& pairs) {
  const Values v = RandomValues({0, 1, 2, 3, 4}, rng);
  const PoseGraph g = Star(v, {1, 2, 3, 4}, {{1, 3}}, rng);
  MatrixXd lambda_N;
  VectorXd g_N;
  EliminateFirstBlock(LinearizeClique(g, v, 0, true, false), &lambda_N, &g_N);
  SmallProblem p;
  p.sigma = lambda_N.bottomRightCorner(9, 9).inverse();
  p.sigma = 0.5 * (p.sigma + p.sigma.transpose()).eval();
  for (const auto& [a, b] : pairs) {
    NfrJacobian j;
    const Pose2& Xa = v.at(static_cast<NodeId>(a + 1));
    const Pose2& Xb = v.at(static_cast<NodeId>(b + 1));
    RelativeErrorJacobians(Xa, Xb, Between(Xa, Xb), &j.J_from, &j.J_to);
    j.from = a - 1;
    j.to = b - 1;
    p.jacobians.push_back(j);
  }
  return p;
}

TEST(Nfr, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(7);
  const SmallProblem p = MakeProblem(&rng, {{0, 1}, {1, 2}, {1, 3}, {0, 2}});
  std::vector<Matrix3d> omega = NfrTreeInformation(p.sigma, p.jacobians);
  omega[3] = 0.3 * omega[0];
  const std::vector<Matrix3d> grad = NfrGradient(p.sigma, p.jacobians, omega);
  for (std::size_t i = 0; i < omega.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      for (int b = a; b < 3; ++b) {
        const double h = 1e-6 * omega[i].norm();
        std::vector<Matrix3d> plus = omega, minus = omega;
        plus[i](a, b) += h;
        minus[i](a, b) -= h;
        if (a != b) {
          plus[i](b, a) += h;
          minus[i](b, a) -= h;
        }
        // f = 2 KL + const; a symmetric off-diagonal change moves two entries.
        const double fd = (NfrKl(p.sigma, p.jacobians, plus) - NfrKl(p.sigma, p.jacobians, minus)) /
                          h;  // 2 KL difference over 2h
        const double analytic = a == b ? grad[i](a, b) : 2.0 * grad[i](a, b);
        EXPECT_NEAR(fd, analytic, 1e-5 * (1.0 + std::abs(analytic)) + 1e-6 * grad[i].norm())
            << i << " " << a << b;
      }
    }
  }
}

TEST(Nfr, SolverResultSatisfiesKkt) {
  // A tree (0-1, 1-2, 1-3) plus two chords. KKT of min f over PSD Omega_i, checked in the
  // whitened variables X_i = S_i^1/2 Omega_i S_i^1/2 (S_i = J_i Sigma J_i^T), gradient
  // G~_i = S_i^-1/2 G_i S_i^-1/2: X_i PSD, G~_i PSD, X_i G~_i = 0 (so G~_i = 0 where X_i is
  // definite). Some optima lie inside the cone, others on its boundary (an edge whose best
  // information is singular); both kinds must occur over the seeds.
  int interior = 0, boundary = 0;
  for (unsigned seed = 11; seed < 21; ++seed) {
    std::mt19937 rng(seed);
    const SmallProblem p = MakeProblem(&rng, {{0, 1}, {1, 2}, {1, 3}, {0, 2}, {2, 3}});
    std::vector<Matrix3d> start = NfrTreeInformation(p.sigma, p.jacobians);
    start[3].setZero();
    start[4].setZero();
    const double tree_kl = NfrKl(p.sigma, p.jacobians, start);
    const NfrResult r = SolveNfr(p.sigma, p.jacobians, start);
    EXPECT_TRUE(r.converged) << "seed " << seed << " kkt " << r.kkt << " after " << r.iterations;
    EXPECT_LT(r.iterations, 40) << seed;
    EXPECT_LT(r.kl, tree_kl - 1e-6) << seed;
    EXPECT_NEAR(r.kl, NfrKl(p.sigma, p.jacobians, r.information), 1e-10);
    const std::vector<Matrix3d> grad = NfrGradient(p.sigma, p.jacobians, r.information);
    bool all_definite = true;
    for (std::size_t i = 0; i < grad.size(); ++i) {
      const Matrix3d s = NfrTreeInformation(p.sigma, {p.jacobians[i]})[0].inverse();
      const Eigen::SelfAdjointEigenSolver<Matrix3d> es(0.5 * (s + s.transpose()));
      const Matrix3d x = es.operatorSqrt() * r.information[i] * es.operatorSqrt();
      const Matrix3d gw = es.operatorInverseSqrt() * grad[i] * es.operatorInverseSqrt();
      const double x_min = Eigen::SelfAdjointEigenSolver<Matrix3d>(x).eigenvalues().minCoeff();
      EXPECT_GE(x_min, -1e-12) << seed << " " << i;
      EXPECT_GE(Eigen::SelfAdjointEigenSolver<Matrix3d>(gw).eigenvalues().minCoeff(), -1e-6)
          << seed << " " << i;
      EXPECT_LT((x * gw).norm(), 1e-6) << seed << " " << i;
      if (x_min > 1e-3) {
        EXPECT_LT(gw.norm(), 1e-5) << seed << " " << i;  // interior edge: gradient zero
      } else {
        all_definite = false;
      }
    }
    (all_definite ? interior : boundary) += 1;
    // No feasible neighbour is better.
    std::normal_distribution<double> n01(0.0, 1.0);
    for (int k = 0; k < 20; ++k) {
      std::vector<Matrix3d> moved = r.information;
      for (Matrix3d& m : moved) {
        Matrix3d d;
        for (int e = 0; e < 9; ++e) d(e / 3, e % 3) = n01(rng);
        d = (d * d.transpose()).eval();  // PSD: stays feasible from the boundary too
        m += (k % 2 == 0 ? 1e-3 : -1e-3) * r.information[0].norm() / d.norm() * d;
      }
      const double kl = NfrKl(p.sigma, p.jacobians, moved);
      if (k % 2 == 0) {
        EXPECT_GE(kl, r.kl - 1e-12) << seed;
      }
    }
  }
  EXPECT_GT(interior, 0);
  EXPECT_GT(boundary, 0);
}

TEST(Nfr, SolverStopsOnTheBoundaryWhenAChordHelpsNothing) {
  // The marginal of a tree (Sigma built from the tree's own factors) with one chord: the
  // chord's best information is 0, a KKT point on the cone's boundary.
  std::mt19937 rng(13);
  SmallProblem p = MakeProblem(&rng, {{0, 1}, {1, 2}, {1, 3}, {0, 3}});
  std::vector<Matrix3d> tree_info;
  for (int i = 0; i < 3; ++i) tree_info.push_back(RandomInfo(&rng));
  const std::vector<NfrJacobian> tree(p.jacobians.begin(), p.jacobians.begin() + 3);
  p.sigma = NfrInformation(tree, tree_info, 9).inverse();
  std::vector<Matrix3d> start = tree_info;
  start.push_back(0.5 * tree_info[0]);  // start the chord away from its optimum
  const NfrResult r = SolveNfr(p.sigma, p.jacobians, start);
  EXPECT_NEAR(r.kl, 0.0, 1e-9);
  EXPECT_LT(r.information[3].norm(), 1e-6 * tree_info[0].norm());
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(r.information[i].isApprox(tree_info[i], 1e-5)) << i;
}

TEST(Nfr, LowRankMarginalIsRegularizedAndFinite) {
  // Node 3 is tied to k only in x: the marginal is singular in 3's (y, theta).
  std::mt19937 rng(2);
  const Values v = RandomValues({0, 1, 2, 3}, &rng);
  PoseGraph g = Star(v, {1, 2}, {{1, 2}}, &rng);
  g.AddEdge(ConsistentEdge(0, 3, v, Eigen::Vector3d(1.0, 0.0, 0.0).asDiagonal()));
  for (const char* name : {"nfr-tree", "nfr-subgraph"}) {
    const Replacement r = MakeSparsifier(name)->Replace(g, v, 0);
    EXPECT_TRUE(r.regularized) << name;
    EXPECT_TRUE(std::isfinite(r.kl_divergence)) << name;
    EXPECT_GE(r.kl_divergence, 0.0);
    EXPECT_GE(r.edges.size(), 2u);
    for (const PoseEdge& e : r.edges) EXPECT_TRUE(e.information.allFinite()) << name;
  }
}

}  // namespace
}  // namespace lifelong::slam
