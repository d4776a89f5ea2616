#include "slam/marginal/glc.hpp"

#include <cmath>
#include <random>
#include <set>
#include <utility>

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

#include "slam/graph/se2.hpp"
#include "slam/marginal/marginalization.hpp"
#include "slam/sparsify/sparsifier.hpp"
#include "tests/slam/marginalization_graphs.hpp"

namespace lifelong::slam {
namespace {

using Eigen::MatrixXd;
using namespace test_util;  // tests/slam/marginalization_graphs.hpp

MatrixXd Marginal(const PoseGraph& g, const Values& v, NodeId k) {
  return SchurComplementFirstBlock(LinearizeAround(g, v, k).H);
}

int Rank(const MatrixXd& m) {
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<MatrixXd>(m).eigenvalues();
  int r = 0;
  for (Eigen::Index i = 0; i < ev.size(); ++i) r += ev(i) > 1e-9 * ev.maxCoeff() ? 1 : 0;
  return r;
}

TEST(GlcDense, ReproducesTheSchurComplement) {
  std::mt19937 rng(4);
  for (int trial = 0; trial < 5; ++trial) {
    const Values v = RandomValues({0, 2, 3, 6, 8}, &rng);
    const PoseGraph g = Star(v, {2, 3, 6, 8}, {}, &rng);
    const MatrixXd lambda = Marginal(g, v, 0);
    const Replacement r = MakeSparsifier("glc-dense")->Replace(g, v, 0);
    ASSERT_EQ(r.cliques.size(), 1u);
    EXPECT_TRUE(r.edges.empty());
    EXPECT_EQ(r.cliques[0].nodes, (std::vector<NodeId>{2, 3, 6, 8}));
    const MatrixXd back = FactorsHessian(r.neighbours, v, r.edges, r.cliques);
    EXPECT_TRUE(back.isApprox(lambda, 1e-9)) << back - lambda;
    EXPECT_NEAR(r.kl_divergence, 0.0, 1e-9);
    EXPECT_EQ(r.Pairs(), 6u);
  }
}

TEST(GlcChowLiu, CliqueThatIsATreeLosesNothing) {
  // k = 5 is a leaf of the tree 1-2, 2-3, 3-4, 2-5, all stored as one dense clique factor:
  // the marginal over {1, 2, 3, 4} is the chain 1-2-3-4. Root-shifted at 1 it is the tree
  // y2 - y3 - y4 with y2's marginal, which the GLC tree reproduces exactly.
  std::mt19937 rng(12);
  for (int trial = 0; trial < 5; ++trial) {
    const Values v = RandomValues({1, 2, 3, 4, 5}, &rng);
    const std::vector<NodeId> all{1, 2, 3, 4, 5};
    MatrixXd h = MatrixXd::Zero(15, 15);
    AddEdgeHessian(ConsistentEdge(1, 2, v, RandomInfo(&rng)), v, all, &h);
    AddEdgeHessian(ConsistentEdge(2, 3, v, RandomInfo(&rng)), v, all, &h);
    AddEdgeHessian(ConsistentEdge(4, 3, v, RandomInfo(&rng)), v, all, &h);
    AddEdgeHessian(ConsistentEdge(2, 5, v, RandomInfo(&rng)), v, all, &h);
    PoseGraph g;
    for (NodeId id : all) g.AddNode(id);
    g.AddClique(ToCliqueFactor(all, v, h));
    const MatrixXd lambda = Marginal(g, v, 5);
    const Replacement r = MakeSparsifier("glc")->Replace(g, v, 5);
    EXPECT_NEAR(r.kl_divergence, 0.0, 1e-9) << "trial " << trial;
    const MatrixXd back = FactorsHessian(r.neighbours, v, r.edges, r.cliques);
    EXPECT_TRUE(back.isApprox(lambda, 1e-8)) << "trial " << trial;
    EXPECT_EQ(r.edges.size() + r.cliques.size(), 3u);  // the root's marginal + 2 conditionals
  }
}

TEST(GlcChowLiu, DenseCliqueLosesSomethingButStaysFinite) {
  std::mt19937 rng(31);
  const Values v = RandomValues({0, 1, 2, 3, 4, 5}, &rng);
  const PoseGraph g = Star(v, {1, 2, 3, 4, 5}, {{1, 3}, {2, 5}}, &rng);
  SparsifierConfig config;
  config.blanket = BlanketPolicy::kFactorsAtK;
  const Replacement glc = MakeSparsifier("glc", config)->Replace(g, v, 0);
  const Replacement dense = MakeSparsifier("glc-dense", config)->Replace(g, v, 0);
  EXPECT_GT(glc.kl_divergence, 1e-6);
  EXPECT_TRUE(std::isfinite(glc.kl_divergence));
  EXPECT_EQ(glc.edges.size() + glc.cliques.size(), 4u);  // m - 1 factors
  // Root-shifted conditionals are ternary factors {r, p, c}: by the gamma count (3 pairs
  // each) the tree is no sparser than the dense clique for m = 5 (1 + 3 * 3 = 10 = 5 * 4 / 2),
  // though it touches only 2m - 3 = 7 distinct pairs, against 10.
  EXPECT_LE(glc.Pairs(), dense.Pairs());
  std::set<std::pair<NodeId, NodeId>> pairs;
  for (const PoseEdge& e : glc.edges) pairs.insert({e.from, e.to});
  for (const CliqueFactor& c : glc.cliques) {
    ASSERT_LE(c.nodes.size(), 3u);
    EXPECT_EQ(c.nodes[0], 1);  // the root
    for (std::size_t a = 0; a < c.nodes.size(); ++a) {
      for (std::size_t b = a + 1; b < c.nodes.size(); ++b) {
        pairs.insert({std::min(c.nodes[a], c.nodes[b]), std::max(c.nodes[a], c.nodes[b])});
      }
    }
  }
  EXPECT_EQ(pairs.size(), 7u);
}

TEST(GlcDense, LowRankMarginalKeepsItsRankWithoutAPrior) {
  // k = 0 sits between 1 and 2 on odometry and sees 3 only in x: the marginal over
  // {1, 2, 3} has rank 3 + 1 = 4 of the 6 root-shifted directions. GLC keeps exactly those
  // (no weak prior fills the other two), and the two-variable tree is exact.
  std::mt19937 rng(2);
  const Values v = RandomValues({0, 1, 2, 3}, &rng);
  PoseGraph g;
  for (NodeId id : {0, 1, 2, 3}) g.AddNode(id);
  g.AddEdge(ConsistentEdge(1, 0, v, RandomInfo(&rng)));
  g.AddEdge(ConsistentEdge(0, 2, v, RandomInfo(&rng)));
  g.AddEdge(ConsistentEdge(0, 3, v, Eigen::Vector3d(5.0, 0.0, 0.0).asDiagonal()));
  const MatrixXd lambda = Marginal(g, v, 0);
  for (const char* name : {"glc-dense", "glc"}) {
    const Replacement r = MakeSparsifier(name)->Replace(g, v, 0);
    const MatrixXd back = FactorsHessian(r.neighbours, v, r.edges, r.cliques);
    EXPECT_TRUE(back.allFinite()) << name;
    EXPECT_TRUE(back.isApprox(lambda, 1e-8)) << name << "\n" << back - lambda;
    EXPECT_EQ(Rank(back), 4) << name;
    EXPECT_FALSE(r.regularized && std::string(name) == "glc-dense");
    EXPECT_NEAR(r.kl_divergence, 0.0, 1e-9) << name;
  }
  int rank = 0;
  InformativePart(ToCliqueFactor({1, 2, 3}, v, lambda).information, 1e-10, &rank);
  EXPECT_EQ(rank, 4);
}

TEST(GlcChowLiu, RankThreeCliquesKeepTheGradientWithinTheirRowSpace) {
  // Issue #12: k = 0 is tied to {1, 2} and {3, 4} only by two rank-3 ternary factors (as
  // GLC conditionals leave them), with residuals. The marginal over {1, 2, 3, 4} has rank 3
  // and couples three relative poses at once, which no pairwise tree expresses: the tree's
  // conditionals came out as rounding noise (~1e-14) and keeping the gradient through them
  // moved their measurements by ~1e14. The replacement must stay finite and small.
  std::mt19937 rng(7);
  const Values v = RandomValues({0, 1, 2, 3, 4}, &rng);
  PoseGraph g;
  for (NodeId id : {0, 1, 2, 3, 4}) g.AddNode(id);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (const std::vector<NodeId>& nodes : {std::vector<NodeId>{1, 2, 0}, {3, 4, 0}}) {
    CliqueFactor c;
    c.nodes = nodes;
    for (std::size_t j = 1; j < nodes.size(); ++j) {
      c.T_root_node.push_back(Between(v.at(nodes[0]), v.at(nodes[j])) *
                              Pose2(noise(rng), noise(rng), noise(rng)));
    }
    const MatrixXd b = MatrixXd::Random(3, 6) * 3.0;
    c.information = b.transpose() * b;  // rank 3 of 6
    g.AddClique(c);
  }
  SparsifierConfig config;
  config.means = FactorMeans::kGradient;
  const Replacement r = MakeSparsifier("glc", config)->Replace(g, v, 0);
  MatrixXd lambda_N;
  Eigen::VectorXd g_N;
  EliminateFirstBlock(LinearizeClique(g, v, 0, true, true), &lambda_N, &g_N);
  EXPECT_EQ(Rank(lambda_N), 3);
  EXPECT_TRUE(std::isfinite(r.kl_divergence));
  const MatrixXd back = FactorsHessian(r.neighbours, v, r.edges, r.cliques);
  EXPECT_TRUE(back.isApprox(lambda_N, 1e-8)) << back - lambda_N;
  for (const CliqueFactor& c : r.cliques) {
    for (std::size_t j = 0; j + 1 < c.nodes.size(); ++j) {
      const Eigen::Vector3d e =
          RelativeError(v.at(c.nodes[0]), v.at(c.nodes[j + 1]), c.T_root_node[j]);
      EXPECT_LT(e.norm(), 1.0) << "a measurement moved far: " << e.transpose();
    }
  }
  for (const PoseEdge& e : r.edges) {
    EXPECT_LT(RelativeError(v.at(e.from), v.at(e.to), e.T_from_to).norm(), 1.0);
  }
}

TEST(InformativeKl, MatchesGaugeFixedKlWhenDefinite) {
  std::mt19937 rng(5);
  const Values v = RandomValues({0, 1, 2, 3, 4}, &rng);
  const PoseGraph g = Star(v, {1, 2, 3, 4}, {}, &rng);
  const MatrixXd lambda = Marginal(g, v, 0);
  const MarginalizationResult cl = MarginalizeChowLiu(g, v, 0);
  const MatrixXd q = FactorsHessian(cl.neighbours, v, cl.edges, {});
  EXPECT_NEAR(InformativeKl(lambda, q, 1e-12), GaugeFixedKl(lambda, q), 1e-9);
  EXPECT_GT(InformativeKl(lambda, q, 1e-12), 1e-6);
}

}  // namespace
}  // namespace lifelong::slam
