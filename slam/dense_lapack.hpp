// The dense kernels needed at the size of a whole kept graph or of a large clique (d = 3 x
// thousands), done by LAPACK / BLAS (OpenBLAS at run time, install-deps.sh) in place: Eigen's
// own kernels took ~13 min and 12 GB for the global KL of city10000 at keep share 0.5
// (d = 15 000).
#pragma once

#include <Eigen/Core>

namespace lifelong::slam {

/// a = L L^T (dpotrf): `a`'s lower triangle becomes L and its upper triangle is zeroed.
/// Only the lower triangle of `a` is read. False if `a` is not positive definite.
bool CholeskyInPlace(Eigen::MatrixXd* a);

/// b = L^-1 b for lower-triangular L (dtrsm), in place.
void SolveLowerInPlace(const Eigen::MatrixXd& L, Eigen::MatrixXd* b);

/// a = V diag(w) V^T for symmetric `a` (dsyevd, divide and conquer): `a` becomes V (the
/// eigenvectors, by column) and w the eigenvalues, ascending. Only the lower triangle of `a`
/// is read. False if it did not converge. Eigen's own solver took about half an hour at the
/// size of a boundary clique of city10000 at keep share 0.25 (d = 7098).
bool SymmetricEigenInPlace(Eigen::MatrixXd* a, Eigen::VectorXd* w);

}  // namespace lifelong::slam
