// Chow-Liu tree of a Gaussian (seed §5.3.2, Chow & Liu 1968): weigh every pair of
// variables by their mutual information (seed eq. 5.35), then keep the maximum-weight
// spanning tree (Kruskal 1956). Variables are blocks of `block` rows (3 for SE(2) poses):
// variable i spans rows [block*i, block*i + block), never row i.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace lifelong::slam {

/// An undirected weighted pair of variables, i < j.
struct WeightedPair {
  int i = 0;
  int j = 0;
  double weight = 0.0;
};

/// A tree edge oriented away from the tree's root: p(child | parent).
struct TreeEdge {
  int parent = 0;
  int child = 0;
  double weight = 0.0;
};

/// Seed eq. (5.35) in nats: I(i,j) = 1/2 ln(|S_ii| |S_jj| / |S_{ij,ij}|), where S is the
/// covariance (symmetric positive definite) and S_{ij,ij} the 2-block joint covariance.
double GaussianMutualInformation(const Eigen::MatrixXd& sigma, int i, int j, int block = 3);

/// All pairs i < j of `num_vars` variables weighted by seed eq. (5.35).
std::vector<WeightedPair> MutualInformationPairs(const Eigen::MatrixXd& sigma, int block = 3);

/// Kruskal's maximum-weight spanning tree (union-find). Ties are broken by (i, j)
/// ascending, so the result is deterministic. If the pairs do not connect all
/// `num_vars` variables the result is a spanning forest (fewer than num_vars - 1 pairs).
std::vector<WeightedPair> MaximumSpanningTree(int num_vars, std::vector<WeightedPair> pairs);

/// Orients tree pairs away from `root` (breadth first, children in ascending order).
std::vector<TreeEdge> OrientTree(int num_vars, const std::vector<WeightedPair>& tree, int root);

/// Chow-Liu tree of N(., sigma) rooted at variable 0: MutualInformationPairs ->
/// MaximumSpanningTree -> OrientTree.
std::vector<TreeEdge> ChowLiuTree(const Eigen::MatrixXd& sigma, int block = 3);

}  // namespace lifelong::slam
