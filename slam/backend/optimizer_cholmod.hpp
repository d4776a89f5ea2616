// CHOLMOD workspace of the back-end (RAII): the upper-triangular block pattern of H in CSC
// form, built and analyzed (fill-reducing ordering, symbolic factorization) once per
// Optimize call, then factorized numerically and solved once per iteration.
// Internal to slam: the API is slam/backend/optimizer.hpp.
#pragma once

#include <cstddef>
#include <vector>

#include <cholmod.h>

#include <Eigen/Core>

#include "slam/backend/optimizer.hpp"
#include "slam/backend/optimizer_problem.hpp"

namespace lifelong::slam::backend {

class Cholmod {
 public:
  Cholmod(const Layout& layout, LinearSolver solver);
  ~Cholmod();
  Cholmod(const Cholmod&) = delete;
  Cholmod& operator=(const Cholmod&) = delete;

  /// Stored entries of H's upper triangle, and the CSC column pointers (3 per block).
  std::size_t Nnz() const { return static_cast<int*>(A_->p)[A_->ncol]; }
  const int* ColPtr() const { return static_cast<const int*>(A_->p); }

  /// Solves (H + lambda D) dx = rhs, D = diag(d); false when not positive definite.
  bool Solve(const std::vector<double>& h, double lambda, const Eigen::VectorXd& d,
             const Eigen::VectorXd& rhs, Eigen::VectorXd* dx);

 private:
  cholmod_common common_{};
  cholmod_sparse* A_ = nullptr;
  cholmod_factor* L_ = nullptr;
  cholmod_dense* b_ = nullptr;
};

}  // namespace lifelong::slam::backend
