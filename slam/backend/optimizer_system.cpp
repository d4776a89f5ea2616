#include "slam/backend/optimizer_system.hpp"

#include <algorithm>
#include <vector>

#include "slam/backend/factor_linearization.hpp"
#include "slam/graph/se2.hpp"

namespace lifelong::slam::backend {

double System::MaxDiagonal() const {
  double m = 0.0;
  for (int j = 0; j < g_.size(); ++j) m = std::max(m, h_[static_cast<std::size_t>(p_[j + 1] - 1)]);
  return m;
}

Eigen::VectorXd System::DampingScale(bool marquardt) const {
  if (!marquardt) return Eigen::VectorXd::Ones(g_.size());
  const double floor = 1e-9 * std::max(MaxDiagonal(), 1e-12);
  Eigen::VectorXd d(g_.size());
  for (Eigen::Index j = 0; j < d.size(); ++j) {
    d[j] = std::max(h_[static_cast<std::size_t>(p_[j + 1] - 1)], floor);
  }
  return d;
}

double System::Linearize(const OptimizerParams& params) {
  std::fill(h_.begin(), h_.end(), 0.0);
  g_.setZero();
  double chi2 = 0.0;
  for (const EdgeSlot& s : layout_.edges) chi2 += LinearizeEdge(s, params);
  for (const CliqueSlot& s : layout_.cliques) chi2 += LinearizeClique(s);
  return chi2;
}

// H_ab += M (rows of block a, columns of block b), a <= b, into the upper triangle.
void System::AddBlock(int a, int b, int rank, const Eigen::Matrix3d& M) {
  for (int c = 0; c < 3; ++c) {
    double* col = h_.data() + p_[3 * b + c] + 3 * rank;
    const int rows = (a == b) ? c + 1 : 3;
    for (int r = 0; r < rows; ++r) col[r] += M(r, c);
  }
}

void System::AddOffDiagonal(int a, int b, int rank, const Eigen::Matrix3d& M_ab) {
  if (rank < 0) return;
  if (a < b) {
    AddBlock(a, b, rank, M_ab);
  } else {
    AddBlock(b, a, rank, M_ab.transpose());
  }
}

void System::AddGradient(int a, const Eigen::Vector3d& v) {
  if (a != kNoBlock) g_.segment<3>(3 * a) += v;
}

double System::LinearizeEdge(const EdgeSlot& s, const OptimizerParams& params) {
  const PoseEdge& edge = *s.edge;
  const Pose2& Xi = Pose(s.i);
  const Pose2& Xj = Pose(s.j);
  const Eigen::Vector3d e = RelativeError(Xi, Xj, edge.T_from_to);
  const KernelValue k = ApplyKernel(e.dot(edge.information * e), edge.robust, params);
  Eigen::Matrix3d Ji, Jj;
  RelativeErrorJacobians(Xi, Xj, edge.T_from_to, &Ji, &Jj);
  const Eigen::Matrix3d W = k.weight * edge.information;
  const Eigen::Matrix3d WJi = W * Ji, WJj = W * Jj;
  const int a = Block(s.i), b = Block(s.j);
  if (a != kNoBlock) AddBlock(a, a, s.rank_ii, Ji.transpose() * WJi);
  if (b != kNoBlock) AddBlock(b, b, s.rank_jj, Jj.transpose() * WJj);
  AddOffDiagonal(a, b, s.rank_ij, Ji.transpose() * WJj);
  const Eigen::Vector3d We = W * e;
  AddGradient(a, Ji.transpose() * We);
  AddGradient(b, Jj.transpose() * We);
  return k.cost;
}

// Root-relative stacked errors (pose_graph.hpp): block row j depends on root and n_j.
double System::LinearizeClique(const CliqueSlot& s) {
  const CliqueFactor& c = *s.clique;
  const std::size_t m = s.nodes.size();
  std::vector<Pose2> poses;
  for (std::size_t u = 0; u < m; ++u) poses.push_back(Pose(s.nodes[u]));
  const CliqueLinearization l = LinearizeCliqueFactor(c, poses, true);  // O(k^2) blocks
  std::size_t pair = 0;
  for (std::size_t u = 0; u < m; ++u) {
    const int a = Block(s.nodes[u]);
    AddGradient(a, l.g(u));
    for (std::size_t v = u; v < m; ++v, ++pair) {
      const int b = Block(s.nodes[v]);
      if (a == kNoBlock || b == kNoBlock) continue;
      const Eigen::Matrix3d M = l.H(u, v);
      if (a == b) {
        // Two clique members share a block only if a node repeats: add both halves.
        AddBlock(a, a, s.ranks[pair], u == v ? M : Eigen::Matrix3d(M + M.transpose()));
      } else {
        AddOffDiagonal(a, b, s.ranks[pair], M);
      }
    }
  }
  return l.e.dot(l.w);
}

}  // namespace lifelong::slam::backend
