#include "slam/dense_lapack.hpp"

#include <gtest/gtest.h>
#include <Eigen/Cholesky>

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
