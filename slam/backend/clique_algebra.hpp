// Small helpers shared by the marginalization and sparsifier sources: where a node's 3 x 3
// block lies in a matrix over a clique, its estimate, and the pseudo-inverse of a PSD matrix.
// Not part of the public API.
#pragma once

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "slam/backend/dense_lapack.hpp"
#include "slam/graph/pose_graph.hpp"

namespace lifelong::slam::clique {

/// First row (and column) of the i-th node's 3 x 3 block.
inline Eigen::Index Block(std::size_t i) { return static_cast<Eigen::Index>(3 * i); }

/// Position of node n in a clique's node list; std::logic_error naming `who` when absent.
inline std::size_t IndexOf(const std::vector<NodeId>& index, NodeId n, const char* who) {
  const auto it = std::find(index.begin(), index.end(), n);
  if (it == index.end()) {
    throw std::logic_error(std::string(who) + ": node " + std::to_string(n) + " not in clique");
  }
  return static_cast<std::size_t>(it - index.begin());
}

/// The estimate of node n; std::logic_error when there is none.
inline const Pose2& At(const Values& values, NodeId n) {
  const auto it = values.find(n);
  if (it == values.end()) {
    throw std::logic_error("marginalization: no estimate for node " + std::to_string(n));
  }
  return it->second;
}

/// Moore-Penrose inverse of a symmetric PSD matrix (eigenvalues below cut * max dropped).
inline Eigen::MatrixXd PinvPsd(const Eigen::MatrixXd& m, double cut = 1e-12) {
  if (m.rows() == 0) return m;
  const SymmetricEigen eig = DecomposeSymmetric(m);
  const Eigen::VectorXd& ev = eig.values;
  const double tol = cut * std::max(ev.cwiseAbs().maxCoeff(), 1e-300);
  Eigen::VectorXd inv = Eigen::VectorXd::Zero(ev.size());
  for (Eigen::Index i = 0; i < ev.size(); ++i) inv(i) = ev(i) > tol ? 1.0 / ev(i) : 0.0;
  return eig.vectors * inv.asDiagonal() * eig.vectors.transpose();
}

}  // namespace lifelong::slam::clique
