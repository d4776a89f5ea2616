#include "slam/optimizer_system.hpp"

#include <algorithm>
#include <vector>

#include "slam/se2.hpp"

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
  const std::size_t k = m - 1;
  const Eigen::MatrixXd& omega = c.information;
  // J is block-sparse: block row j holds the root's Jacobian R_j (column block 0) and node
  // j+1's N_j (column block j+1). So H = J^T Omega J block by block in O(k^2), not the
  // O(k^3) of dense products (minutes per iteration for a clique over 2367 nodes):
  //   H_00 = R^T Omega R,  H_0,b+1 = R^T Omega_:b N_b,  H_a+1,b+1 = N_a^T Omega_ab N_b.
  Eigen::VectorXd e(3 * k);
  Eigen::MatrixXd R(3 * k, 3);
  std::vector<Eigen::Matrix3d> N(k);
  const Pose2& Xr = Pose(s.nodes[0]);
  for (std::size_t j = 0; j < k; ++j) {
    const auto row = static_cast<Eigen::Index>(3 * j);
    const Pose2& Xn = Pose(s.nodes[j + 1]);
    e.segment<3>(row) = RelativeError(Xr, Xn, c.T_root_node[j]);
    Eigen::Matrix3d Jr;
    RelativeErrorJacobians(Xr, Xn, c.T_root_node[j], &Jr, &N[j]);
    R.block<3, 3>(row, 0) = Jr;
  }
  const Eigen::MatrixXd omega_r = omega * R;
  std::vector<Eigen::MatrixXd> omega_n(k);  // Omega's block column b times N_b
  for (std::size_t b = 0; b < k; ++b) {
    omega_n[b] = omega.middleCols<3>(static_cast<Eigen::Index>(3 * b)) * N[b];
  }
  const auto block = [&](std::size_t u, std::size_t v) -> Eigen::Matrix3d {  // H_uv, u <= v
    if (u == 0)
      return v == 0 ? Eigen::Matrix3d(R.transpose() * omega_r)
                    : Eigen::Matrix3d(R.transpose() * omega_n[v - 1]);
    return N[u - 1].transpose() *
           omega_n[v - 1].middleRows<3>(static_cast<Eigen::Index>(3 * (u - 1)));
  };
  const Eigen::VectorXd w = omega * e;
  std::size_t pair = 0;
  for (std::size_t u = 0; u < m; ++u) {
    const int a = Block(s.nodes[u]);
    AddGradient(a, u == 0 ? Eigen::Vector3d(R.transpose() * w)
                          : Eigen::Vector3d(N[u - 1].transpose() *
                                            w.segment<3>(static_cast<Eigen::Index>(3 * (u - 1)))));
    for (std::size_t v = u; v < m; ++v, ++pair) {
      const int b = Block(s.nodes[v]);
      if (a == kNoBlock || b == kNoBlock) continue;
      const Eigen::Matrix3d M = block(u, v);
      if (a == b) {
        // Two clique members share a block only if a node repeats: add both halves.
        AddBlock(a, a, s.ranks[pair], u == v ? M : Eigen::Matrix3d(M + M.transpose()));
      } else {
        AddOffDiagonal(a, b, s.ranks[pair], M);
      }
    }
  }
  return e.dot(w);
}

}  // namespace lifelong::slam::backend
