#include "slam/marginal/chow_liu.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <set>
#include <utility>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>

namespace lifelong::slam {
namespace {

using Eigen::MatrixXd;

MatrixXd RandomSpd(int dim, std::mt19937* rng) {
  std::normal_distribution<double> n01(0.0, 1.0);
  MatrixXd a(dim, dim);
  for (int r = 0; r < dim; ++r) {
    for (int c = 0; c < dim; ++c) a(r, c) = n01(*rng);
  }
  return a * a.transpose() + 0.5 * MatrixXd::Identity(dim, dim);
}

double TreeWeight(const std::vector<WeightedPair>& tree) {
  double w = 0.0;
  for (const WeightedPair& p : tree) w += p.weight;
  return w;
}

/// Brute force: the heaviest subset of n-1 pairs that connects all n vertices.
double BruteForceMaxTreeWeight(int n, const std::vector<WeightedPair>& pairs) {
  const int num_pairs = static_cast<int>(pairs.size());
  double best = -1e300;
  for (int mask = 0; mask < (1 << num_pairs); ++mask) {
    if (__builtin_popcount(static_cast<unsigned>(mask)) != n - 1) continue;
    std::vector<int> parent(static_cast<std::size_t>(n));
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int a) {
      while (parent[static_cast<std::size_t>(a)] != a) a = parent[static_cast<std::size_t>(a)];
      return a;
    };
    bool acyclic = true;
    double w = 0.0;
    for (int e = 0; e < num_pairs && acyclic; ++e) {
      if ((mask & (1 << e)) == 0) continue;
      const WeightedPair& p = pairs[static_cast<std::size_t>(e)];
      const int a = find(p.i), b = find(p.j);
      acyclic = a != b;
      parent[static_cast<std::size_t>(a)] = b;
      w += p.weight;
    }
    if (acyclic) best = std::max(best, w);  // n-1 acyclic edges on n vertices span them
  }
  return best;
}

TEST(GaussianMutualInformation, MatchesPerCoordinateCorrelations) {
  // Two 3-dim variables, coordinate k of one correlated with coordinate k of the other
  // only, with correlation rho_k: I = -1/2 sum_k ln(1 - rho_k^2).
  const double rho[3] = {0.5, 0.8, 0.0};
  MatrixXd sigma = MatrixXd::Identity(6, 6);
  for (int k = 0; k < 3; ++k) sigma(k, 3 + k) = sigma(3 + k, k) = rho[k];
  const double expected = -0.5 * (std::log(1 - 0.25) + std::log(1 - 0.64));
  EXPECT_NEAR(GaussianMutualInformation(sigma, 0, 1), expected, 1e-12);
  EXPECT_NEAR(GaussianMutualInformation(sigma, 1, 0), expected, 1e-12);
}

TEST(GaussianMutualInformation, UsesThreeByThreeBlocksNotRows) {
  // Variables 0, 1, 2 (rows 0-2, 3-5, 6-8); only variables 1 and 2 are correlated. A
  // row-indexing bug (variable i at row i) would read rows 1-2 and 2-3 and see nothing.
  MatrixXd sigma = MatrixXd::Identity(9, 9);
  sigma(3, 6) = sigma(6, 3) = 0.6;
  EXPECT_NEAR(GaussianMutualInformation(sigma, 1, 2), -0.5 * std::log(1 - 0.36), 1e-12);
  EXPECT_NEAR(GaussianMutualInformation(sigma, 0, 1), 0.0, 1e-12);
  EXPECT_NEAR(GaussianMutualInformation(sigma, 0, 2), 0.0, 1e-12);
}

TEST(MaximumSpanningTree, HandExample) {
  // Square 0-1-2-3 with diagonals; heaviest acyclic picks: (0,2)=5, (1,3)=4, (0,1)=3.
  const std::vector<WeightedPair> pairs = {{0, 1, 3.0}, {1, 2, 1.0}, {2, 3, 2.0},
                                           {0, 3, 0.5}, {0, 2, 5.0}, {1, 3, 4.0}};
  const std::vector<WeightedPair> tree = MaximumSpanningTree(4, pairs);
  ASSERT_EQ(tree.size(), 3u);
  EXPECT_EQ(std::make_pair(tree[0].i, tree[0].j), std::make_pair(0, 2));
  EXPECT_EQ(std::make_pair(tree[1].i, tree[1].j), std::make_pair(1, 3));
  EXPECT_EQ(std::make_pair(tree[2].i, tree[2].j), std::make_pair(0, 1));
  EXPECT_DOUBLE_EQ(TreeWeight(tree), 12.0);
}

TEST(MaximumSpanningTree, TiesAreBrokenByPairIndex) {
  const std::vector<WeightedPair> pairs = {{1, 2, 1.0}, {0, 2, 1.0}, {0, 1, 1.0}};
  const std::vector<WeightedPair> tree = MaximumSpanningTree(3, pairs);
  ASSERT_EQ(tree.size(), 2u);
  EXPECT_EQ(std::make_pair(tree[0].i, tree[0].j), std::make_pair(0, 1));
  EXPECT_EQ(std::make_pair(tree[1].i, tree[1].j), std::make_pair(0, 2));
}

TEST(ChowLiuTree, HasMaximumWeightAgainstBruteForce) {
  std::mt19937 rng(42);
  for (int m : {4, 5}) {
    for (int trial = 0; trial < 20; ++trial) {
      const MatrixXd sigma = RandomSpd(3 * m, &rng);
      const std::vector<WeightedPair> pairs = MutualInformationPairs(sigma);
      ASSERT_EQ(pairs.size(), static_cast<std::size_t>(m * (m - 1) / 2));
      const std::vector<WeightedPair> tree = MaximumSpanningTree(m, pairs);
      ASSERT_EQ(tree.size(), static_cast<std::size_t>(m - 1));
      EXPECT_NEAR(TreeWeight(tree), BruteForceMaxTreeWeight(m, pairs), 1e-12)
          << "m=" << m << " trial=" << trial;
    }
  }
}

TEST(ChowLiuTree, RecoversATreeStructuredGaussian) {
  // Information with the sparsity of the tree 0-2, 2-1, 2-3, 3-4: the Chow-Liu tree of
  // its covariance is that tree (Chow & Liu 1968).
  std::mt19937 rng(7);
  const std::set<std::pair<int, int>> truth = {{0, 2}, {1, 2}, {2, 3}, {3, 4}};
  MatrixXd lambda = MatrixXd::Zero(15, 15);
  for (const auto& [a, b] : truth) {
    const MatrixXd f = RandomSpd(6, &rng);  // a pairwise factor over (a, b)
    const int idx[2] = {a, b};
    for (int u = 0; u < 2; ++u) {
      for (int v = 0; v < 2; ++v) {
        lambda.block(3 * idx[u], 3 * idx[v], 3, 3) += f.block(3 * u, 3 * v, 3, 3);
      }
    }
  }
  const MatrixXd sigma = lambda.llt().solve(MatrixXd::Identity(15, 15));
  const std::vector<TreeEdge> tree = ChowLiuTree(sigma);
  ASSERT_EQ(tree.size(), 4u);
  std::set<std::pair<int, int>> found;
  for (const TreeEdge& e : tree)
    found.insert({std::min(e.parent, e.child), std::max(e.parent, e.child)});
  EXPECT_EQ(found, truth);
}

TEST(OrientTree, PointsAwayFromTheRoot) {
  const std::vector<WeightedPair> tree = {{0, 2, 1.0}, {1, 2, 1.0}, {2, 3, 1.0}};
  const std::vector<TreeEdge> oriented = OrientTree(4, tree, 1);
  ASSERT_EQ(oriented.size(), 3u);
  EXPECT_EQ(oriented[0].parent, 1);
  EXPECT_EQ(oriented[0].child, 2);
  EXPECT_EQ(oriented[1].parent, 2);
  EXPECT_EQ(oriented[1].child, 0);
  EXPECT_EQ(oriented[2].parent, 2);
  EXPECT_EQ(oriented[2].child, 3);
}

}  // namespace
}  // namespace lifelong::slam
