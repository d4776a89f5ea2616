// Linearization of the pose graph for the back-end: H (straight into the CSC value array of
// optimizer_cholmod's pattern) and g = J^T W Omega e, from the factors' analytic Jacobians
// (se2.hpp), robust edges weighted by the kernel's IRLS weight.
// Internal to slam: the API is slam/backend/optimizer.hpp.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "slam/backend/optimizer.hpp"
#include "slam/backend/optimizer_problem.hpp"

namespace lifelong::slam::backend {

class System {
 public:
  /// H is stored in the CSC value array of the pattern given by `colptr` (nnz entries).
  System(const Layout& layout, const int* colptr, std::size_t nnz)
      : layout_(layout), p_(colptr), h_(nnz), g_(3 * layout.num_blocks) {}

  const std::vector<double>& H() const { return h_; }
  const Eigen::VectorXd& g() const { return g_; }
  double MaxDiagonal() const;

  /// LM damping scale: diag(H) clamped away from zero (Marquardt), or all ones.
  Eigen::VectorXd DampingScale(bool marquardt) const;

  /// Fills H and g at the current poses and returns chi2 there.
  double Linearize(const OptimizerParams& params);

 private:
  int Block(int node) const { return layout_.block[static_cast<std::size_t>(node)]; }
  const Pose2& Pose(int node) const { return *layout_.poses[static_cast<std::size_t>(node)]; }

  void AddBlock(int a, int b, int rank, const Eigen::Matrix3d& M);
  void AddOffDiagonal(int a, int b, int rank, const Eigen::Matrix3d& M_ab);
  void AddGradient(int a, const Eigen::Vector3d& v);
  double LinearizeEdge(const EdgeSlot& s, const OptimizerParams& params);
  double LinearizeClique(const CliqueSlot& s);

  const Layout& layout_;
  const int* p_;
  std::vector<double> h_;
  Eigen::VectorXd g_;
};

}  // namespace lifelong::slam::backend
