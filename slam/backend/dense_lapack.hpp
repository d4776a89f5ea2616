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

/// m = vectors diag(values) vectors^T for symmetric m (its lower triangle is read), values
/// ascending.
/// Eigen's solver up to kLapackEigenFrom rows, SymmetricEigenInPlace above, where Eigen's
/// takes minutes to hours. The switch is by size so that small cliques keep their results:
/// which eigenvalues fall below a tolerance's cut can flip with rounding, and over thousands
/// of removals that moves glc's KLD by a few per cent (intel at 0.25: 28.7 nats, 29.8 with
/// LAPACK for every clique).
constexpr Eigen::Index kLapackEigenFrom = 300;
struct SymmetricEigen {
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
};
SymmetricEigen DecomposeSymmetric(const Eigen::MatrixXd& m);
/// The eigenvalues alone, ascending, with the same switch of solver.
Eigen::VectorXd SymmetricEigenvalues(const Eigen::MatrixXd& m);

}  // namespace lifelong::slam
