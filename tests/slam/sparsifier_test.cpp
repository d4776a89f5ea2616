#include "slam/sparsify/sparsifier.hpp"

#include <cstring>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>

#include "slam/graph/se2.hpp"
#include "slam/marginal/marginalization.hpp"
#include "tests/slam/marginalization_graphs.hpp"

namespace lifelong::slam {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using namespace test_util;  // tests/slam/marginalization_graphs.hpp

bool SameBytes(const Pose2& a, const Pose2& b) {
  return a.x == b.x && a.y == b.y && a.theta == b.theta;
}

/// 1/2 sum e^T Omega e of the factors at v.
double Cost(const std::vector<PoseEdge>& edges, const std::vector<CliqueFactor>& cliques,
            const Values& v) {
  double c = 0.0;
  for (const PoseEdge& e : edges) {
    const Eigen::Vector3d r = RelativeError(v.at(e.from), v.at(e.to), e.T_from_to);
    c += 0.5 * r.dot(e.information * r);
  }
  for (const CliqueFactor& f : cliques) {
    VectorXd r(f.information.rows());
    for (std::size_t j = 0; j + 1 < f.nodes.size(); ++j) {
      r.segment<3>(static_cast<Eigen::Index>(3 * j)) =
          RelativeError(v.at(f.nodes[0]), v.at(f.nodes[j + 1]), f.T_root_node[j]);
    }
    c += 0.5 * r.dot(f.information * r);
  }
  return c;
}

/// A star around 0 whose measurements disagree with the estimate (nonzero residuals).
PoseGraph NoisyStar(const Values& v, std::mt19937* rng) {
  PoseGraph g = Star(v, {1, 2, 3, 4}, {{1, 3}}, rng);
  PoseGraph noisy;
  for (NodeId id : g.NodeIds()) noisy.AddNode(id);
  std::normal_distribution<double> n(0.0, 0.05);
  for (PoseEdge e : g.edges()) {
    e.T_from_to = e.T_from_to * Pose2(n(*rng), n(*rng), n(*rng));
    noisy.AddEdge(e);
  }
  return noisy;
}

TEST(Sparsifier, RegistryNamesEveryMethod) {
  EXPECT_EQ(SparsifierNames(), (std::vector<std::string>{"naive", "exact", "chow-liu", "glc-dense",
                                                         "glc", "nfr-tree", "nfr-subgraph"}));
  for (const std::string& name : SparsifierNames()) {
    const auto s = MakeSparsifier(name);
    ASSERT_NE(s, nullptr) << name;
    EXPECT_EQ(s->Name(), name);
  }
  EXPECT_EQ(MakeSparsifier("chow_liu"), nullptr);
}

TEST(Sparsifier, WrappersGiveTheMappersFactorsByteForByte) {
  std::mt19937 rng(41);
  const Values v = RandomValues({0, 1, 2, 3, 4}, &rng);
  const PoseGraph g = NoisyStar(v, &rng);
  using MarginalizeFn = MarginalizationResult (*)(const PoseGraph&, const Values&, NodeId);
  const std::pair<const char*, MarginalizeFn> methods[] = {
      {"naive", MarginalizeNaive},
      {"exact", MarginalizeExact},
      {"chow-liu", [](const PoseGraph& graph, const Values& values, NodeId k) {
         return MarginalizeChowLiu(graph, values, k, BlanketPolicy::kBlanket);
       }}};
  for (const auto& [name, marginalize] : methods) {
    const MarginalizationResult m = marginalize(g, v, 0);
    const Replacement r = MakeSparsifier(name)->Replace(g, v, 0);
    ASSERT_EQ(r.edges.size(), m.edges.size()) << name;
    for (std::size_t i = 0; i < m.edges.size(); ++i) {
      EXPECT_TRUE(SameBytes(r.edges[i].T_from_to, m.edges[i].T_from_to)) << name;
      EXPECT_EQ(0, std::memcmp(r.edges[i].information.data(), m.edges[i].information.data(),
                               9 * sizeof(double)));
    }
    ASSERT_EQ(r.cliques.size(), m.clique ? 1u : 0u) << name;
    if (m.clique) {
      EXPECT_TRUE(r.cliques[0].information == m.clique->information);
    }
    EXPECT_EQ(r.kl_divergence, m.kl_divergence) << name;
    EXPECT_EQ(r.absorb_edges_within, m.absorbed_blanket) << name;
    EXPECT_EQ(r.Pairs(), m.num_pairs) << name;
  }
}

// The gradient of r's factors at v over r.neighbours, by central differences.
VectorXd CostGradient(const Replacement& r, const Values& v) {
  VectorXd grad(3 * static_cast<Eigen::Index>(r.neighbours.size()));
  for (Eigen::Index c = 0; c < grad.size(); ++c) {
    Values plus = v, minus = v;
    const NodeId id = r.neighbours[static_cast<std::size_t>(c / 3)];
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d(c % 3) = 1e-6;
    plus[id] = V2T(T2V(v.at(id)) + d);
    minus[id] = V2T(T2V(v.at(id)) - d);
    grad(c) = (Cost(r.edges, r.cliques, plus) - Cost(r.edges, r.cliques, minus)) / 2e-6;
  }
  return grad;
}

// The Gauss-Newton step of (H, g) with node 0 held: where that quadratic has its minimum.
VectorXd HeldStep(const MatrixXd& H, const VectorXd& g) {
  const Eigen::Index d = H.rows() - 3;
  return -H.bottomRightCorner(d, d).ldlt().solve(g.tail(d));
}

// The exact marginal of node 0's clique as method `name` replaces it: with the factors among
// the neighbours for the blanket methods, and their clique factors for GLC.
void ExactMarginalAsSeenBy(const std::string& name, const PoseGraph& g, const Values& v,
                           MatrixXd* lambda_N, VectorXd* g_N) {
  const bool blanket = name == "chow-liu" || name == "glc" || name == "glc-dense" ||
                       name == "nfr-tree" || name == "nfr-subgraph";
  const bool cliques = name == "glc" || name == "glc-dense";
  EliminateFirstBlock(LinearizeClique(g, v, 0, blanket, cliques), lambda_N, g_N);
}

TEST(Sparsifier, KeepGradientKeepsTheHessianAndMatchesTheMarginalsGradient) {
  std::mt19937 rng(43);
  const Values v = RandomValues({0, 1, 2, 3, 4}, &rng);
  const PoseGraph g = NoisyStar(v, &rng);
  SparsifierConfig config;
  config.means = FactorMeans::kGradient;
  for (const std::string& name : SparsifierNames()) {
    MatrixXd lambda_N;
    VectorXd g_N;
    ExactMarginalAsSeenBy(name, g, v, &lambda_N, &g_N);
    const Replacement plain = MakeSparsifier(name)->Replace(g, v, 0);
    const Replacement kept = MakeSparsifier(name, config)->Replace(g, v, 0);
    const std::vector<NodeId>& n = kept.neighbours;
    EXPECT_TRUE(FactorsHessian(n, v, kept.edges, kept.cliques)
                    .isApprox(FactorsHessian(n, v, plain.edges, plain.cliques), 1e-9))
        << name;
    const VectorXd grad = CostGradient(kept, v);
    // Every replacement here spans N (definite with node 0 held), so the whole gradient of
    // the exact marginal is kept, whatever the method lost in information.
    EXPECT_TRUE(grad.isApprox(g_N, 1e-5)) << name << "\n" << (grad - g_N).transpose();
    EXPECT_GT(g_N.norm(), 1e-3);  // the test has something to keep
  }
}

TEST(Sparsifier, KeepMeanPutsTheFactorsMinimumAtTheMarginalsMean) {
  std::mt19937 rng(47);
  const Values v = RandomValues({0, 1, 2, 3, 4}, &rng);
  const PoseGraph g = NoisyStar(v, &rng);
  SparsifierConfig mean, gradient;
  mean.means = FactorMeans::kMarginalMean;
  gradient.means = FactorMeans::kGradient;
  for (const std::string& name : SparsifierNames()) {
    MatrixXd lambda_N;
    VectorXd g_N;
    ExactMarginalAsSeenBy(name, g, v, &lambda_N, &g_N);
    const Replacement kept = MakeSparsifier(name, mean)->Replace(g, v, 0);
    const MatrixXd h = FactorsHessian(kept.neighbours, v, kept.edges, kept.cliques);
    const VectorXd want = HeldStep(lambda_N, g_N), got = HeldStep(h, CostGradient(kept, v));
    EXPECT_GT(want.norm(), 1e-3) << name;  // the marginal's mean is not the estimate
    EXPECT_TRUE(got.isApprox(want, 1e-4)) << name << "\n"
                                          << got.transpose() << "\n"
                                          << want.transpose();
    // A method that keeps the marginal's information keeps its gradient too, and the other
    // way round: then both modes give the same factors.
    if (name == "exact" || name == "glc-dense") {
      const Replacement by_gradient = MakeSparsifier(name, gradient)->Replace(g, v, 0);
      EXPECT_TRUE(CostGradient(by_gradient, v).isApprox(CostGradient(kept, v), 1e-5)) << name;
    }
  }
}

// A measurement carries a heading residual inside (-pi, pi] only. When the gradient asks
// for a target past it (here e_theta = 2.9 rad plus 0.4 rad of displacement), that part of
// the gradient is given up and the factor keeps its own gradient. Judging the displacement
// alone (0.4 rad) let the target wrap to -2.98 rad: a gradient neither kept nor the old one.
// Nor is a part of it kept: the whole step or nothing.
TEST(Sparsifier, KeepGradientNeverWrapsAHeadingResidual) {
  const Values v{{0, Pose2()}, {1, Pose2(1.0, 0.0, 0.0)}};
  PoseEdge edge;
  edge.from = 0;
  edge.to = 1;
  edge.T_from_to = Pose2(1.0, 0.0, -2.9);
  const Eigen::Vector3d e = RelativeError(v.at(0), v.at(1), edge.T_from_to);
  ASSERT_NEAR(e.z(), 2.9, 1e-12);
  Eigen::Matrix3d J0, J1;
  RelativeErrorJacobians(v.at(0), v.at(1), edge.T_from_to, &J0, &J1);
  MatrixXd J(3, 6);
  J << J0, J1;
  const VectorXd own = J.transpose() * e;  // information I
  VectorXd z = VectorXd::Zero(6);
  z(5) = 0.4;  // node 1's heading
  const VectorXd asked = J.transpose() * (e + J * z);
  std::vector<PoseEdge> edges{edge};
  std::vector<CliqueFactor> cliques;
  PreserveGradient({0, 1}, v, asked, &edges, &cliques);
  ASSERT_EQ(edges.size(), 1u);
  const Eigen::Vector3d after = RelativeError(v.at(0), v.at(1), edges[0].T_from_to);
  Eigen::Matrix3d K0, K1;
  RelativeErrorJacobians(v.at(0), v.at(1), edges[0].T_from_to, &K0, &K1);
  MatrixXd K(3, 6);
  K << K0, K1;
  const VectorXd grad = K.transpose() * (edges[0].information * after);
  EXPECT_TRUE(grad.isApprox(own, 1e-9)) << grad.transpose() << "\n" << own.transpose();
  // All or nothing: a reachable part of the step (0.05 m along x) is not kept on its own.
  z(3) = 0.05;
  z(5) = 0.4;
  edges = {edge};
  PreserveGradient({0, 1}, v, J.transpose() * (e + J * z), &edges, &cliques);
  RelativeErrorJacobians(v.at(0), v.at(1), edges[0].T_from_to, &K0, &K1);
  K << K0, K1;
  const Eigen::Vector3d kept = RelativeError(v.at(0), v.at(1), edges[0].T_from_to);
  EXPECT_TRUE((K.transpose() * (edges[0].information * kept)).isApprox(own, 1e-9));
  z(3) = 0.0;
  // A step the measurement can carry is still kept whole.
  z(5) = -0.4;
  const VectorXd reachable = J.transpose() * (e + J * z);
  edges = {edge};
  PreserveGradient({0, 1}, v, reachable, &edges, &cliques);
  RelativeErrorJacobians(v.at(0), v.at(1), edges[0].T_from_to, &K0, &K1);
  K << K0, K1;
  const Eigen::Vector3d moved = RelativeError(v.at(0), v.at(1), edges[0].T_from_to);
  EXPECT_TRUE((K.transpose() * (edges[0].information * moved)).isApprox(reachable, 1e-9));
}

// The moved factors may hold no more error than the factors they replace (the exact marginal
// never does), plus one unit per coordinate. Here the marginal is weak (unit information) and
// the new edge stiff (1e4): moved to the marginal's mean, 1 m off, the edge would hold chi2 1e4
// against the 2 + 6 allowed, and the back-end would be pulled by what no factor said. It keeps
// measuring x* instead.
TEST(Sparsifier, MovedFactorsHoldNoMoreErrorThanTheReplacedOnes) {
  const Values v{{0, Pose2()}, {1, Pose2(1.0, 0.0, 0.0)}};
  PoseEdge edge;
  edge.from = 0;
  edge.to = 1;
  edge.T_from_to = Between(v.at(0), v.at(1));
  edge.information = 1e4 * Eigen::Matrix3d::Identity();
  MatrixXd lambda_N(6, 6);
  lambda_N << Eigen::Matrix3d::Identity(), -Eigen::Matrix3d::Identity(),
      -Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity();
  VectorXd g_N = VectorXd::Zero(6);
  g_N(3) = 1.0;  // the marginal's mean: node 1 one metre along x
  std::vector<CliqueFactor> cliques;
  std::vector<PoseEdge> edges{edge};
  PreserveGradient({0, 1}, v, g_N, &edges, &cliques, &lambda_N, 2.0);
  EXPECT_LT(RelativeError(v.at(0), v.at(1), edges[0].T_from_to).norm(), 1e-12);
  // Without the bound it moves by the metre.
  edges = {edge};
  PreserveGradient({0, 1}, v, g_N, &edges, &cliques, &lambda_N);
  EXPECT_NEAR(RelativeError(v.at(0), v.at(1), edges[0].T_from_to).norm(), 1.0, 1e-6);
}

}  // namespace
}  // namespace lifelong::slam
