#include "slam/backend/dense_lapack.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include <Eigen/Eigenvalues>

extern "C" {
// Fortran LAPACK / BLAS (column-major, every argument by pointer, string lengths appended).
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info,
             std::size_t uplo_len);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m,
            const int* n, const double* alpha, const double* a, const int* lda, double* b,
            const int* ldb, std::size_t side_len, std::size_t uplo_len, std::size_t transa_len,
            std::size_t diag_len);
void dsyevd_(const char* jobz, const char* uplo, const int* n, double* a, const int* lda, double* w,
             double* work, const int* lwork, int* iwork, const int* liwork, int* info,
             std::size_t jobz_len, std::size_t uplo_len);
}

namespace lifelong::slam {

bool CholeskyInPlace(Eigen::MatrixXd* a) {
  if (a->rows() != a->cols()) throw std::invalid_argument("CholeskyInPlace: not square");
  const int n = static_cast<int>(a->rows());
  if (n == 0) return true;
  int info = 0;
  dpotrf_("L", &n, a->data(), &n, &info, 1);
  a->triangularView<Eigen::StrictlyUpper>().setZero();
  return info == 0;
}

void SolveLowerInPlace(const Eigen::MatrixXd& L, Eigen::MatrixXd* b) {
  if (L.rows() != L.cols() || b->rows() != L.rows()) {
    throw std::invalid_argument("SolveLowerInPlace: sizes differ");
  }
  const int m = static_cast<int>(b->rows()), n = static_cast<int>(b->cols());
  if (m == 0 || n == 0) return;
  const double one = 1.0;
  dtrsm_("L", "L", "N", "N", &m, &n, &one, L.data(), &m, b->data(), &m, 1, 1, 1, 1);
}

namespace {

/// dsyevd on `a` (lower triangle read): jobz "V" leaves the eigenvectors in `a`, "N" only the
/// eigenvalues in w. False if it did not converge.
bool Dsyevd(const char* jobz, Eigen::MatrixXd* a, Eigen::VectorXd* w) {
  if (a->rows() != a->cols()) throw std::invalid_argument("dsyevd: not square");
  const int n = static_cast<int>(a->rows());
  w->resize(n);
  if (n == 0) return true;
  int info = 0, lwork = -1, liwork = -1, iwork_size = 0;
  double work_size = 0.0;  // a workspace query first
  dsyevd_(jobz, "L", &n, a->data(), &n, w->data(), &work_size, &lwork, &iwork_size, &liwork, &info,
          1, 1);
  if (info != 0) return false;
  lwork = std::max(static_cast<int>(work_size), 1);
  liwork = std::max(iwork_size, 1);
  std::vector<double> work(static_cast<std::size_t>(lwork));
  std::vector<int> iwork(static_cast<std::size_t>(liwork));
  dsyevd_(jobz, "L", &n, a->data(), &n, w->data(), work.data(), &lwork, iwork.data(), &liwork,
          &info, 1, 1);
  return info == 0;
}

}  // namespace

bool SymmetricEigenInPlace(Eigen::MatrixXd* a, Eigen::VectorXd* w) { return Dsyevd("V", a, w); }

SymmetricEigen DecomposeSymmetric(const Eigen::MatrixXd& m) {
  SymmetricEigen d{Eigen::VectorXd(), m};
  if (m.rows() > kLapackEigenFrom && Dsyevd("V", &d.vectors, &d.values)) return d;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(m);
  return {eig.eigenvalues(), eig.eigenvectors()};
}

Eigen::VectorXd SymmetricEigenvalues(const Eigen::MatrixXd& m) {
  if (m.rows() > kLapackEigenFrom) {
    Eigen::MatrixXd a = m;
    Eigen::VectorXd w;
    if (Dsyevd("N", &a, &w)) return w;
  }
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(m, Eigen::EigenvaluesOnly).eigenvalues();
}

}  // namespace lifelong::slam
