// The Hessians (and gradient) of single factors scattered into a local system; declared in
// marginalization.hpp.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "slam/clique_algebra.hpp"
#include "slam/marginalization.hpp"
#include "slam/se2.hpp"

namespace lifelong::slam {
namespace {

using clique::At;
using clique::Block;

using Eigen::Matrix3d;
using Eigen::MatrixXd;

}  // namespace

void AddEdgeHessian(const PoseEdge& edge, const Values& values, const std::vector<NodeId>& index,
                    MatrixXd* H) {
  Matrix3d Ji, Jj;
  RelativeErrorJacobians(At(values, edge.from), At(values, edge.to), edge.T_from_to, &Ji, &Jj);
  const Eigen::Index a = Block(clique::IndexOf(index, edge.from, "marginalization"));
  const Eigen::Index b = Block(clique::IndexOf(index, edge.to, "marginalization"));
  const Matrix3d& omega = edge.information;
  H->block<3, 3>(a, a) += Ji.transpose() * omega * Ji;
  H->block<3, 3>(a, b) += Ji.transpose() * omega * Jj;
  H->block<3, 3>(b, a) += Jj.transpose() * omega * Ji;
  H->block<3, 3>(b, b) += Jj.transpose() * omega * Jj;
}

void AddCliqueHessian(const CliqueFactor& clique, const Values& values,
                      const std::vector<NodeId>& index, MatrixXd* H) {
  AddCliqueLinearized(clique, values, index, H, nullptr);
}

void AddCliqueLinearized(const CliqueFactor& clique, const Values& values,
                         const std::vector<NodeId>& index, MatrixXd* H, Eigen::VectorXd* g) {
  const std::size_t k = clique.nodes.size() - 1;
  const Pose2& Xr = At(values, clique.nodes[0]);
  const Eigen::Index r = Block(clique::IndexOf(index, clique.nodes[0], "marginalization"));
  const MatrixXd& omega = clique.information;
  MatrixXd R(Block(k), 3);                         // the root's Jacobian blocks, stacked
  std::vector<Matrix3d> N(k);                      // node j's Jacobian (block row j only)
  std::vector<Eigen::Index> at(k);                 // node j's block in H
  Eigen::VectorXd e(g != nullptr ? Block(k) : 0);  // the errors, for the gradient only
  for (std::size_t j = 0; j < k; ++j) {
    const NodeId n = clique.nodes[j + 1];
    Matrix3d Jr;
    RelativeErrorJacobians(Xr, At(values, n), clique.T_root_node[j], &Jr, &N[j]);
    R.block<3, 3>(Block(j), 0) = Jr;
    at[j] = Block(clique::IndexOf(index, n, "marginalization"));
    if (g != nullptr)
      e.segment<3>(Block(j)) = RelativeError(Xr, At(values, n), clique.T_root_node[j]);
  }
  // Columns of Omega J: the root's (Omega R), node b's (Omega's block column b times N_b).
  const MatrixXd omega_r = omega * R;
  std::vector<MatrixXd> omega_n(k);
  for (std::size_t b = 0; b < k; ++b) omega_n[b] = omega.middleCols<3>(Block(b)) * N[b];
  H->block<3, 3>(r, r) += R.transpose() * omega_r;
  for (std::size_t b = 0; b < k; ++b) {
    const Matrix3d rb = R.transpose() * omega_n[b];
    H->block<3, 3>(r, at[b]) += rb;
    H->block<3, 3>(at[b], r) += rb.transpose();
    for (std::size_t a = 0; a < k; ++a) {
      H->block<3, 3>(at[a], at[b]) += N[a].transpose() * omega_n[b].middleRows<3>(Block(a));
    }
  }
  if (g == nullptr) return;
  const Eigen::VectorXd w = omega * e;
  g->segment<3>(r) += R.transpose() * w;
  for (std::size_t j = 0; j < k; ++j)
    g->segment<3>(at[j]) += N[j].transpose() * w.segment<3>(Block(j));
}

}  // namespace lifelong::slam
