#include "slam/backend/dense_lapack.hpp"

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace lifelong::slam {
namespace {

TEST(DenseLapack, CholeskyAndSolveMatchEigen) {
  const Eigen::MatrixXd m = Eigen::MatrixXd::Random(40, 40);
  const Eigen::MatrixXd a = m * m.transpose() + 40.0 * Eigen::MatrixXd::Identity(40, 40);
  Eigen::MatrixXd L = a;
  L.triangularView<Eigen::StrictlyUpper>().setConstant(7.0);  // never read
  ASSERT_TRUE(CholeskyInPlace(&L));
  const Eigen::MatrixXd eigen_L = Eigen::LLT<Eigen::MatrixXd>(a).matrixL();
  EXPECT_TRUE(L.isApprox(eigen_L, 1e-12));
  EXPECT_TRUE(L.triangularView<Eigen::StrictlyUpper>().toDenseMatrix().isZero(0.0));
  Eigen::MatrixXd b = Eigen::MatrixXd::Random(40, 7);
  const Eigen::MatrixXd expected = eigen_L.triangularView<Eigen::Lower>().solve(b);
  SolveLowerInPlace(L, &b);
  EXPECT_TRUE(b.isApprox(expected, 1e-12));
}

TEST(DenseLapack, SymmetricEigenMatchesEigen) {
  const Eigen::MatrixXd m = Eigen::MatrixXd::Random(30, 12);
  const Eigen::MatrixXd a = m * m.transpose();  // rank 12 of 30: 18 zero eigenvalues
  Eigen::MatrixXd v = a;
  v.triangularView<Eigen::StrictlyUpper>().setConstant(7.0);  // never read
  Eigen::VectorXd w;
  ASSERT_TRUE(SymmetricEigenInPlace(&v, &w));
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(a);
  EXPECT_TRUE(w.isApprox(eig.eigenvalues(), 1e-10) ||
              (w - eig.eigenvalues()).cwiseAbs().maxCoeff() < 1e-10 * a.norm());
  for (int i = 1; i < w.size(); ++i) EXPECT_LE(w(i - 1), w(i));  // ascending
  EXPECT_TRUE((v * w.asDiagonal() * v.transpose()).isApprox(a, 1e-10));
  EXPECT_TRUE((v.transpose() * v).isApprox(Eigen::MatrixXd::Identity(30, 30), 1e-10));
  EXPECT_NEAR(w.head(18).cwiseAbs().maxCoeff(), 0.0, 1e-10 * a.norm());
}

TEST(DenseLapack, CholeskyReportsAnIndefiniteMatrix) {
  Eigen::MatrixXd a(2, 2);
  a << 1.0, 2.0, 2.0, 1.0;  // eigenvalues 3 and -1
  EXPECT_FALSE(CholeskyInPlace(&a));
  Eigen::MatrixXd empty(0, 0);
  EXPECT_TRUE(CholeskyInPlace(&empty));
  Eigen::MatrixXd wide(2, 3);
  EXPECT_THROW(CholeskyInPlace(&wide), std::invalid_argument);
}

}  // namespace
}  // namespace lifelong::slam
