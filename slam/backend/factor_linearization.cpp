// The Hessians (and gradient) of single factors scattered into a local system.
#include "slam/backend/factor_linearization.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "slam/backend/clique_algebra.hpp"
#include "slam/graph/se2.hpp"

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

CliqueLinearization LinearizeCliqueFactor(const CliqueFactor& clique,
                                          const std::vector<Pose2>& poses, bool gradient) {
  const std::size_t k = clique.nodes.size() - 1;
  const MatrixXd& lambda = clique.information;
  CliqueLinearization l;
  l.R.resize(Block(k), 3);
  l.N.resize(k);
  if (gradient) l.e.resize(Block(k));
  for (std::size_t j = 0; j < k; ++j) {
    Matrix3d Jr;
    RelativeErrorJacobians(poses[0], poses[j + 1], clique.T_root_node[j], &Jr, &l.N[j]);
    l.R.block<3, 3>(Block(j), 0) = Jr;
    if (gradient) {
      l.e.segment<3>(Block(j)) = RelativeError(poses[0], poses[j + 1], clique.T_root_node[j]);
    }
  }
  l.lambda_r = lambda * l.R;
  l.lambda_n.resize(k);
  for (std::size_t b = 0; b < k; ++b) l.lambda_n[b] = lambda.middleCols<3>(Block(b)) * l.N[b];
  if (gradient) l.w = lambda * l.e;
  return l;
}

Matrix3d CliqueLinearization::H(std::size_t u, std::size_t v) const {
  if (u == 0 && v == 0) return R.transpose() * lambda_r;
  if (u == 0) return R.transpose() * lambda_n[v - 1];
  if (v == 0) return (R.transpose() * lambda_n[u - 1]).transpose();
  return N[u - 1].transpose() * lambda_n[v - 1].middleRows<3>(Block(u - 1));
}

Eigen::Vector3d CliqueLinearization::g(std::size_t u) const {
  if (u == 0) return R.transpose() * w;
  return N[u - 1].transpose() * w.segment<3>(Block(u - 1));
}

double AddCliqueLinearized(const CliqueFactor& clique, const Values& values,
                           const std::vector<NodeId>& index, MatrixXd* H, Eigen::VectorXd* g) {
  std::vector<Pose2> poses;
  std::vector<Eigen::Index> at;  // member u's block in H
  for (NodeId n : clique.nodes) {
    poses.push_back(At(values, n));
    at.push_back(Block(clique::IndexOf(index, n, "marginalization")));
  }
  const CliqueLinearization l = LinearizeCliqueFactor(clique, poses, g != nullptr);
  for (std::size_t u = 0; u < at.size(); ++u) {
    for (std::size_t v = 0; v < at.size(); ++v) H->block<3, 3>(at[u], at[v]) += l.H(u, v);
    if (g != nullptr) g->segment<3>(at[u]) += l.g(u);
  }
  return g != nullptr ? l.e.dot(l.w) : 0.0;
}

}  // namespace lifelong::slam
