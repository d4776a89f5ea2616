#include "slam/backend/optimizer_cholmod.hpp"

#include <cstring>

namespace lifelong::slam::backend {

Cholmod::Cholmod(const Layout& layout, LinearSolver solver) {
  cholmod_start(&common_);
  common_.print = 0;  // library code never prints
  // CHOLMOD picks simplicial or supernodal by the factor's density (supernodal wins on
  // lattice-like graphs such as many passes through one corridor, simplicial on sparse
  // ones) and tries METIS after AMD when AMD's fill is poor (docs/bench/backend.md).
  switch (solver) {
    case LinearSolver::kSimplicial:
      common_.supernodal = CHOLMOD_SIMPLICIAL;
      break;
    case LinearSolver::kSupernodal:
      common_.supernodal = CHOLMOD_SUPERNODAL;
      break;
    case LinearSolver::kAuto:
      common_.supernodal = CHOLMOD_AUTO;
      break;
  }
  const std::size_t n = 3 * static_cast<std::size_t>(layout.num_blocks);
  std::size_t nnz = 0;
  for (const auto& rows : layout.rows_of_col) nnz += 9 * rows.size() + 6;
  A_ = cholmod_allocate_sparse(n, n, nnz, 1, 1, 1, CHOLMOD_REAL, &common_);
  b_ = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &common_);
  int* p = static_cast<int*>(A_->p);
  int* rows_out = static_cast<int*>(A_->i);
  int pos = 0;
  for (std::size_t b = 0; b < layout.rows_of_col.size(); ++b) {
    for (int c = 0; c < 3; ++c) {
      p[3 * b + static_cast<std::size_t>(c)] = pos;
      for (int a : layout.rows_of_col[b]) {
        for (int r = 0; r < 3; ++r) rows_out[pos++] = 3 * a + r;
      }
      for (int r = 0; r <= c; ++r) rows_out[pos++] = static_cast<int>(3 * b) + r;
    }
  }
  p[n] = pos;
  L_ = cholmod_analyze(A_, &common_);
}

Cholmod::~Cholmod() {
  cholmod_free_factor(&L_, &common_);
  cholmod_free_sparse(&A_, &common_);
  cholmod_free_dense(&b_, &common_);
  cholmod_finish(&common_);
}

bool Cholmod::Solve(const std::vector<double>& h, double lambda, const Eigen::VectorXd& d,
                    const Eigen::VectorXd& rhs, Eigen::VectorXd* dx) {
  double* x = static_cast<double*>(A_->x);
  std::memcpy(x, h.data(), h.size() * sizeof(double));
  const int* p = ColPtr();
  for (std::size_t j = 0; j < A_->ncol; ++j) {
    x[p[j + 1] - 1] += lambda * d[static_cast<Eigen::Index>(j)];
  }
  cholmod_factorize(A_, L_, &common_);
  if (common_.status != CHOLMOD_OK || L_->minor < L_->n) return false;
  std::memcpy(b_->x, rhs.data(), static_cast<std::size_t>(rhs.size()) * sizeof(double));
  cholmod_dense* sol = cholmod_solve(CHOLMOD_A, L_, b_, &common_);
  if (sol == nullptr) return false;
  *dx = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(sol->x), rhs.size());
  cholmod_free_dense(&sol, &common_);
  return dx->allFinite();
}

}  // namespace lifelong::slam::backend
