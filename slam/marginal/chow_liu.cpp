#include "slam/marginal/chow_liu.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>
#include <stdexcept>

#include <Eigen/Cholesky>

namespace lifelong::slam {
namespace {

double LogDetSpd(const Eigen::MatrixXd& m) {
  Eigen::LLT<Eigen::MatrixXd> llt(m);
  if (llt.info() != Eigen::Success) {
    throw std::domain_error("GaussianMutualInformation: covariance block is not positive definite");
  }
  return 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
}

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(static_cast<std::size_t>(n)) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int Find(int a) {
    while (parent_[Idx(a)] != a) {
      parent_[Idx(a)] = parent_[Idx(parent_[Idx(a)])];  // path halving
      a = parent_[Idx(a)];
    }
    return a;
  }
  bool Unite(int a, int b) {
    a = Find(a);
    b = Find(b);
    if (a == b) return false;
    parent_[Idx(std::max(a, b))] = std::min(a, b);
    return true;
  }

 private:
  static std::size_t Idx(int a) { return static_cast<std::size_t>(a); }
  std::vector<int> parent_;
};

}  // namespace

double GaussianMutualInformation(const Eigen::MatrixXd& sigma, int i, int j, int block) {
  const int d = block;
  Eigen::MatrixXd joint(2 * d, 2 * d);
  joint.topLeftCorner(d, d) = sigma.block(d * i, d * i, d, d);
  joint.topRightCorner(d, d) = sigma.block(d * i, d * j, d, d);
  joint.bottomLeftCorner(d, d) = sigma.block(d * j, d * i, d, d);
  joint.bottomRightCorner(d, d) = sigma.block(d * j, d * j, d, d);
  const double mi = 0.5 * (LogDetSpd(joint.topLeftCorner(d, d)) +
                           LogDetSpd(joint.bottomRightCorner(d, d)) - LogDetSpd(joint));
  return std::max(mi, 0.0);  // >= 0 in exact arithmetic; clamp rounding only
}

std::vector<WeightedPair> MutualInformationPairs(const Eigen::MatrixXd& sigma, int block) {
  const int n = static_cast<int>(sigma.rows()) / block;
  std::vector<WeightedPair> pairs;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      pairs.push_back({i, j, GaussianMutualInformation(sigma, i, j, block)});
    }
  }
  return pairs;
}

std::vector<WeightedPair> MaximumSpanningTree(int num_vars, std::vector<WeightedPair> pairs) {
  std::sort(pairs.begin(), pairs.end(), [](const WeightedPair& a, const WeightedPair& b) {
    if (a.weight != b.weight) return a.weight > b.weight;
    return a.i != b.i ? a.i < b.i : a.j < b.j;
  });
  UnionFind sets(num_vars);
  std::vector<WeightedPair> tree;
  for (const WeightedPair& p : pairs) {
    if (static_cast<int>(tree.size()) + 1 >= num_vars) break;
    if (sets.Unite(p.i, p.j)) tree.push_back(p);
  }
  return tree;
}

std::vector<TreeEdge> OrientTree(int num_vars, const std::vector<WeightedPair>& tree, int root) {
  std::vector<std::vector<std::pair<int, double>>> adjacent(static_cast<std::size_t>(num_vars));
  for (const WeightedPair& p : tree) {
    adjacent[static_cast<std::size_t>(p.i)].emplace_back(p.j, p.weight);
    adjacent[static_cast<std::size_t>(p.j)].emplace_back(p.i, p.weight);
  }
  for (auto& a : adjacent) std::sort(a.begin(), a.end());
  std::vector<bool> seen(static_cast<std::size_t>(num_vars), false);
  std::vector<TreeEdge> out;
  std::queue<int> frontier;
  frontier.push(root);
  seen[static_cast<std::size_t>(root)] = true;
  while (!frontier.empty()) {
    const int p = frontier.front();
    frontier.pop();
    for (const auto& [c, w] : adjacent[static_cast<std::size_t>(p)]) {
      if (seen[static_cast<std::size_t>(c)]) continue;
      seen[static_cast<std::size_t>(c)] = true;
      out.push_back({p, c, w});
      frontier.push(c);
    }
  }
  return out;
}

std::vector<TreeEdge> ChowLiuTree(const Eigen::MatrixXd& sigma, int block) {
  const int n = static_cast<int>(sigma.rows()) / block;
  return OrientTree(n, MaximumSpanningTree(n, MutualInformationPairs(sigma, block)), 0);
}

}  // namespace lifelong::slam
