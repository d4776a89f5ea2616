#include "slam/marginal/marginalization.hpp"

#include <cmath>
#include <random>
#include <set>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "slam/graph/se2.hpp"
#include "slam/marginal/chow_liu.hpp"
#include "tests/slam/marginalization_graphs.hpp"

namespace lifelong::slam {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using namespace test_util;  // tests/slam/marginalization_graphs.hpp

// The three approximations, by name, for tests that hold for each.
using MarginalizeFn = MarginalizationResult (*)(const PoseGraph&, const Values&, NodeId);
const std::pair<const char*, MarginalizeFn> kMethods[] = {
    {"exact", MarginalizeExact},
    {"chow-liu",
     [](const PoseGraph& g, const Values& v, NodeId k) { return MarginalizeChowLiu(g, v, k); }},
    {"naive", MarginalizeNaive}};

MatrixXd DenseSchur(const MatrixXd& H) {  // Eigen reference: eliminate the first block
  const Eigen::Index n = H.rows() - 3;
  const MatrixXd hkk_inv = H.topLeftCorner(3, 3).inverse();
  return H.bottomRightCorner(n, n) - H.bottomLeftCorner(n, 3) * hkk_inv * H.topRightCorner(3, n);
}

TEST(LinearizeAround, PlacesBlockIAtRowThreeI) {
  // All poses at the origin: J_from = -I, J_to = +I, so edge k-n adds [W -W; -W W].
  Values v{{0, {}}, {1, {}}, {2, {}}, {3, {}}};
  PoseGraph g;
  for (NodeId id : {0, 1, 2, 3}) g.AddNode(id);
  const Matrix3d w1 = Eigen::Vector3d(1, 2, 3).asDiagonal();
  const Matrix3d w2 = Eigen::Vector3d(10, 20, 30).asDiagonal();
  const Matrix3d w3 = Eigen::Vector3d(100, 200, 300).asDiagonal();
  g.AddEdge(ConsistentEdge(0, 1, v, w1));
  g.AddEdge(ConsistentEdge(2, 0, v, w2));
  g.AddEdge(ConsistentEdge(0, 3, v, w3));
  const LocalHessian local = LinearizeAround(g, v, 0);
  EXPECT_EQ(local.neighbours, (std::vector<NodeId>{1, 2, 3}));
  ASSERT_EQ(local.H.rows(), 12);
  EXPECT_TRUE(local.H.block(0, 0, 3, 3).isApprox(w1 + w2 + w3));
  EXPECT_TRUE(local.H.block(0, 3, 3, 3).isApprox(-w1));
  EXPECT_TRUE(local.H.block(6, 0, 3, 3).isApprox(-w2));
  EXPECT_TRUE(local.H.block(9, 9, 3, 3).isApprox(w3));
  EXPECT_TRUE(local.H.block(3, 6, 3, 3).isZero());
}

TEST(Marginalize, LinearChainReproducesTheHandSchurComplement) {
  // a=1 - k=0 - b=2 at the origin, diagonal informations wa = 1, wb = 3 per coordinate:
  // Lambda_N = [[wa wb/(wa+wb), -wa wb/(wa+wb)], [.., ..]] = 3/4 [[1, -1], [-1, 1]].
  Values v{{0, {}}, {1, {}}, {2, {}}};
  PoseGraph g;
  for (NodeId id : {0, 1, 2}) g.AddNode(id);
  g.AddEdge(ConsistentEdge(1, 0, v, Matrix3d::Identity()));
  g.AddEdge(ConsistentEdge(0, 2, v, 3.0 * Matrix3d::Identity()));
  MatrixXd H = MatrixXd::Zero(9, 9);  // by hand, order [k, a, b]
  H.block(0, 0, 3, 3) = 4.0 * Matrix3d::Identity();
  H.block(0, 3, 3, 3) = H.block(3, 0, 3, 3) = -Matrix3d::Identity();
  H.block(0, 6, 3, 3) = H.block(6, 0, 3, 3) = -3.0 * Matrix3d::Identity();
  H.block(3, 3, 3, 3) = Matrix3d::Identity();
  H.block(6, 6, 3, 3) = 3.0 * Matrix3d::Identity();
  const LocalHessian local = LinearizeAround(g, v, 0);
  EXPECT_TRUE(local.H.isApprox(H, 1e-12));
  const MatrixXd lambda = SchurComplementFirstBlock(local.H);
  EXPECT_TRUE(lambda.isApprox(DenseSchur(H), 1e-12));
  EXPECT_NEAR(lambda(0, 0), 0.75, 1e-12);
  EXPECT_NEAR(lambda(0, 3), -0.75, 1e-12);
  EXPECT_NEAR(lambda(5, 5), 0.75, 1e-12);
  // Root-relative clique at the origin: J = I, so its information is the (b, b) block.
  const MarginalizationResult r = MarginalizeExact(g, v, 0);
  ASSERT_TRUE(r.clique.has_value());
  EXPECT_EQ(r.clique->nodes, (std::vector<NodeId>{1, 2}));
  EXPECT_TRUE(r.clique->information.isApprox(0.75 * Matrix3d::Identity(), 1e-12));
}

TEST(LinearizeAround, MatchesNumericalJacobians) {
  std::mt19937 rng(3);
  const Values v = RandomValues({0, 1, 2, 3}, &rng);
  const PoseGraph g = Star(v, {1, 2, 3}, {{1, 2}}, &rng);
  const LocalHessian local = LinearizeAround(g, v, 0);
  MatrixXd H = MatrixXd::Zero(12, 12);
  const std::vector<NodeId> order{0, 1, 2, 3};
  for (std::size_t e : g.EdgesOf(0)) {  // J by central differences, H = J^T Omega J
    const PoseEdge& edge = g.edges()[e];
    MatrixXd J = MatrixXd::Zero(3, 12);
    for (int c = 0; c < 12; ++c) {
      Values plus = v, minus = v;
      const NodeId n = order[static_cast<std::size_t>(c / 3)];
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      d(c % 3) = 1e-6;
      plus[n] = V2T(T2V(v.at(n)) + d);
      minus[n] = V2T(T2V(v.at(n)) - d);
      J.col(c) = (RelativeError(plus.at(edge.from), plus.at(edge.to), edge.T_from_to) -
                  RelativeError(minus.at(edge.from), minus.at(edge.to), edge.T_from_to)) /
                 2e-6;
    }
    H += J.transpose() * edge.information * J;
  }
  EXPECT_TRUE(local.H.isApprox(H, 1e-6)) << local.H - H;
}

TEST(Marginalize, ExactCliqueLinearizesBackToTheSchurComplement) {
  std::mt19937 rng(11);
  const Values v = RandomValues({0, 4, 5, 7, 9}, &rng);
  const PoseGraph g = Star(v, {4, 5, 7, 9}, {{5, 7}}, &rng);
  const MatrixXd lambda = SchurComplementFirstBlock(LinearizeAround(g, v, 0).H);
  const MarginalizationResult r = MarginalizeExact(g, v, 0);
  ASSERT_TRUE(r.clique.has_value());
  EXPECT_EQ(r.clique_size, 4u);
  EXPECT_EQ(r.num_pairs, 6u);
  EXPECT_EQ(r.kl_divergence, 0.0);
  EXPECT_TRUE(r.edges.empty());
  EXPECT_EQ(r.clique->nodes.front(), 4);     // root: the smallest id
  const Pose2 z = r.clique->T_root_node[2];  // node 9 relative to root 4
  EXPECT_NEAR(z.x, Between(v.at(4), v.at(9)).x, 1e-12);
  MatrixXd back = MatrixXd::Zero(12, 12);
  AddCliqueHessian(*r.clique, v, {4, 5, 7, 9}, &back);
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd dx = Eigen::VectorXd::Random(12);
    dx.head<3>().setZero();  // root held fixed
    EXPECT_NEAR(dx.dot(back * dx), dx.dot(lambda * dx), 1e-9 * dx.dot(lambda * dx));
  }
  // Both are gauge free, so they agree without fixing the root too.
  EXPECT_TRUE(back.isApprox(lambda, 1e-9));
  // The neighbours' own edge 5-7 is untouched: the applied graph keeps it plus the clique.
  PoseGraph applied = g;
  ApplyMarginalization(&applied, 0, r);
  EXPECT_FALSE(applied.HasNode(0));
  EXPECT_EQ(applied.edges().size(), 1u);
  EXPECT_EQ(applied.cliques().size(), 1u);
  EXPECT_EQ(applied.NumEdgesForGamma(), 7u);
}

TEST(Marginalize, LeafDropsOut) {
  std::mt19937 rng(5);
  const Values v = RandomValues({0, 1, 2}, &rng);
  PoseGraph g = Star(v, {1}, {{1, 2}}, &rng);
  for (const auto& [method, marginalize] : kMethods) {
    const MarginalizationResult r = marginalize(g, v, 0);
    EXPECT_EQ(r.clique_size, 1u);
    EXPECT_TRUE(r.edges.empty());
    EXPECT_FALSE(r.clique.has_value());
    EXPECT_EQ(r.kl_divergence, 0.0);
  }
  ApplyMarginalization(&g, 0, MarginalizeChowLiu(g, v, 0));
  EXPECT_EQ(g.NumNodes(), 2u);
  EXPECT_EQ(g.edges().size(), 1u);
}

TEST(Marginalize, TwoNeighboursLoseNothing) {
  // The marginal over two nodes is a single pair: Chow-Liu and naive composition are exact.
  std::mt19937 rng(9);
  const Values v = RandomValues({0, 3, 8}, &rng);
  const PoseGraph g = Star(v, {3, 8}, {}, &rng);
  const MatrixXd lambda = SchurComplementFirstBlock(LinearizeAround(g, v, 0).H);
  for (const auto& [method, marginalize] : kMethods) {
    if (std::string(method) == "exact") continue;  // a clique, not edges
    const MarginalizationResult r = marginalize(g, v, 0);
    ASSERT_EQ(r.edges.size(), 1u);
    EXPECT_EQ(r.edges[0].kind, EdgeKind::kMarginal);
    EXPECT_NEAR(r.kl_divergence, 0.0, 1e-9);
    MatrixXd q = MatrixXd::Zero(6, 6);
    AddEdgeHessian(r.edges[0], v, {3, 8}, &q);
    EXPECT_TRUE(q.isApprox(lambda, 1e-9)) << method;
    const Pose2 truth = Between(v.at(r.edges[0].from), v.at(r.edges[0].to));
    EXPECT_NEAR(RelativeError(Pose2(), truth, r.edges[0].T_from_to).norm(), 0.0, 1e-12);
  }
}

TEST(Marginalize, ChowLiuIsExactWhenTheMarginalIsATree) {
  // Nodes 1, 2, 3 and k = 4 share one dense clique factor that encodes the tree
  // 1-2, 2-3, 1-4 (pruned-exact mode). Marginalizing the leaf 4 leaves the tree 1-2-3.
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
  const MarginalizationResult r = MarginalizeChowLiu(g, v, 4);
  EXPECT_EQ(r.clique_size, 3u);
  EXPECT_NEAR(r.kl_divergence, 0.0, 1e-9);
  std::set<std::pair<NodeId, NodeId>> pairs;
  for (const PoseEdge& e : r.edges) pairs.insert({std::min(e.from, e.to), std::max(e.from, e.to)});
  EXPECT_EQ(pairs, (std::set<std::pair<NodeId, NodeId>>{{1, 2}, {2, 3}}));
}

TEST(Marginalize, KlIsPositiveForDenseCliquesAndChowLiuBeatsNaive) {
  // Chow-Liu edges carry the exact conditionals of the best tree, so no other tree (the
  // naive star included) can be closer to the exact marginal.
  std::mt19937 rng(33);
  for (int trial = 0; trial < 10; ++trial) {
    const Values v = RandomValues({0, 1, 2, 3, 4, 5}, &rng);
    const PoseGraph g = Star(v, {1, 2, 3, 4, 5}, {{1, 3}, {2, 5}}, &rng);
    const MarginalizationResult cl = MarginalizeChowLiu(g, v, 0);
    const MarginalizationResult nv = MarginalizeNaive(g, v, 0);
    EXPECT_EQ(cl.edges.size(), 4u);
    EXPECT_EQ(nv.edges.size(), 4u);
    EXPECT_GT(cl.kl_divergence, 1e-6);
    EXPECT_TRUE(std::isfinite(cl.kl_divergence));
    EXPECT_LE(cl.kl_divergence, nv.kl_divergence + 1e-9) << "trial " << trial;
  }
}

TEST(Marginalize, RankDeficientSpokeGivesFiniteResults) {
  // Node 3 is tied to k only in x: the marginal is singular in 3's (y, theta). The
  // documented regularization kicks in; nothing may come out NaN.
  std::mt19937 rng(2);
  const Values v = RandomValues({0, 1, 2, 3}, &rng);
  PoseGraph g = Star(v, {1, 2}, {}, &rng);
  g.AddEdge(ConsistentEdge(0, 3, v, Eigen::Vector3d(1.0, 0.0, 0.0).asDiagonal()));
  for (const auto& [method, marginalize] : kMethods) {
    const MarginalizationResult r = marginalize(g, v, 0);
    EXPECT_FALSE(std::isnan(r.kl_divergence)) << method;
    EXPECT_GE(r.kl_divergence, 0.0);
    for (const PoseEdge& e : r.edges) EXPECT_TRUE(e.information.allFinite());
    if (r.clique) {
      EXPECT_TRUE(r.clique->information.allFinite());
    }
  }
  EXPECT_TRUE(MarginalizeChowLiu(g, v, 0).regularized);
}

TEST(Marginalize, ChowLiuTreeHasTheSmallestKlOfAllSpanningTrees) {
  // Chow & Liu: with exact conditionals on every edge, the maximum-MI tree minimizes
  // KL(p || q). Enumerate all 16 spanning trees of 4 neighbours (subsets of 3 of the 6
  // pairs that join all nodes) and compare.
  std::mt19937 rng(77);
  const std::vector<NodeId> nodes{1, 2, 3, 4};
  for (int trial = 0; trial < 5; ++trial) {
    const Values v = RandomValues({0, 1, 2, 3, 4}, &rng);
    const PoseGraph g = Star(v, nodes, {}, &rng);
    const MatrixXd lambda = SchurComplementFirstBlock(LinearizeAround(g, v, 0).H);
    std::vector<WeightedPair> all;
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) all.push_back({i, j, 0.0});
    }
    double best = 1e300;
    int trees = 0;
    for (int mask = 0; mask < 64; ++mask) {
      std::vector<WeightedPair> tree;
      for (int e = 0; e < 6; ++e) {
        if (mask & (1 << e)) tree.push_back(all[static_cast<std::size_t>(e)]);
      }
      if (tree.size() != 3u) continue;
      const std::vector<PoseEdge> edges = ConditionalTreeEdges(nodes, v, lambda, tree);
      if (edges.size() != 3u) continue;  // not spanning (OrientTree missed a node)
      ++trees;
      MatrixXd q = MatrixXd::Zero(12, 12);
      for (const PoseEdge& e : edges) AddEdgeHessian(e, v, nodes, &q);
      best = std::min(best, GaugeFixedKl(lambda, q));
    }
    EXPECT_EQ(trees, 16);  // Cayley: 4^(4-2)
    const MarginalizationResult r = MarginalizeChowLiu(g, v, 0);
    EXPECT_NEAR(r.kl_divergence, best, 1e-9) << "trial " << trial;
  }
}

TEST(CliquePairWeights, EqualWeakPriorMutualInformationUpToOneConstant) {
  // Seed eq. (5.35) under a weak prior eps*I differs from the gauge-free weight by the
  // same constant for every pair (marginalization.hpp), so both give the same tree.
  std::mt19937 rng(8);
  const Values v = RandomValues({0, 1, 2, 3, 4}, &rng);
  const PoseGraph g = Star(v, {1, 2, 3, 4}, {{1, 2}}, &rng);
  const MatrixXd lambda = SchurComplementFirstBlock(LinearizeAround(g, v, 0).H);
  const MatrixXd w = CliquePairWeights({1, 2, 3, 4}, v, lambda);
  const double eps = 1e-6;
  const MatrixXd sigma =
      (lambda + eps * MatrixXd::Identity(12, 12)).llt().solve(MatrixXd::Identity(12, 12));
  const double offset = GaussianMutualInformation(sigma, 0, 1) - w(0, 1);
  EXPECT_GT(offset, 10.0);  // the divergent part, ~3/2 ln(1/eps)
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) {
      EXPECT_NEAR(GaussianMutualInformation(sigma, i, j) - w(i, j), offset, 1e-3) << i << j;
    }
  }
}

}  // namespace
}  // namespace lifelong::slam
