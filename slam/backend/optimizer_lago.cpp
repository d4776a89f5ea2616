#include "slam/backend/optimizer_lago.hpp"

#include <algorithm>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

namespace lifelong::slam::backend {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

// Adds w * (x_b - x_a - c)^T M (x_b - x_a - c) for k-dimensional blocks a, b (kNoBlock: fixed,
// its value folded into c by the caller) to the normal equations H x = rhs.
template <int K>
void AddDifference(int a, int b, const Eigen::Matrix<double, K, K>& M,
                   const Eigen::Matrix<double, K, 1>& c, Triplets* H, Eigen::VectorXd* rhs) {
  for (int r = 0; r < K; ++r) {
    for (int q = 0; q < K; ++q) {
      if (a != kNoBlock) H->emplace_back(K * a + r, K * a + q, M(r, q));
      if (b != kNoBlock) H->emplace_back(K * b + r, K * b + q, M(r, q));
      if (a != kNoBlock && b != kNoBlock) {
        H->emplace_back(K * a + r, K * b + q, -M(r, q));
        H->emplace_back(K * b + r, K * a + q, -M(r, q));
      }
    }
  }
  const Eigen::Matrix<double, K, 1> Mc = M * c;
  if (a != kNoBlock) rhs->template segment<K>(K * a) -= Mc;
  if (b != kNoBlock) rhs->template segment<K>(K * b) += Mc;
}

bool SolveSparse(int n, const Triplets& triplets, const Eigen::VectorXd& rhs, Eigen::VectorXd* x) {
  SparseMatrix H(n, n);
  H.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(H);
  if (ldlt.info() != Eigen::Success) return false;
  *x = ldlt.solve(rhs);
  return ldlt.info() == Eigen::Success && x->allFinite();
}

double MarginalHeadingInformation(const Eigen::Matrix3d& omega) {
  const Eigen::LDLT<Eigen::Matrix2d> tt(omega.topLeftCorner<2, 2>());
  if (tt.info() != Eigen::Success || !(tt.vectorD().minCoeff() > 0.0)) return omega(2, 2);
  const Eigen::Vector2d c = omega.block<2, 1>(0, 2);
  return std::max(omega(2, 2) - c.dot(tt.solve(c)), 0.0);
}

}  // namespace

bool InitializeHeadings(const Layout& layout) {
  Triplets H;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(layout.num_blocks), delta;
  for (const EdgeSlot& s : layout.edges) {
    const Pose2& Xi = *layout.poses[static_cast<std::size_t>(s.i)];
    const Pose2& Xj = *layout.poses[static_cast<std::size_t>(s.j)];
    // Unknowns are heading increments d: residual e + d_j - d_i, i.e. c = -e.
    const double e = NormalizeAngle(Xj.theta - Xi.theta - s.edge->T_from_to.theta);
    const Eigen::Matrix<double, 1, 1> w(MarginalHeadingInformation(s.edge->information));
    AddDifference<1>(layout.block[static_cast<std::size_t>(s.i)],
                     layout.block[static_cast<std::size_t>(s.j)], w,
                     Eigen::Matrix<double, 1, 1>(-e), &H, &rhs);
  }
  if (!SolveSparse(layout.num_blocks, H, rhs, &delta)) return false;
  for (std::size_t k = 0; k < layout.poses.size(); ++k) {
    const int a = layout.block[k];
    if (a == kNoBlock) continue;
    Pose2& x = *layout.poses[k];
    x = Pose2(x.x, x.y, x.theta + delta[a]);
  }
  return true;
}

bool InitializePositions(const Layout& layout) {
  Triplets H;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * layout.num_blocks), t;
  for (const EdgeSlot& s : layout.edges) {
    const Pose2& Xi = *layout.poses[static_cast<std::size_t>(s.i)];
    const Pose2& Xj = *layout.poses[static_cast<std::size_t>(s.j)];
    const Pose2& Z = s.edge->T_from_to;
    const Eigen::Matrix2d Ri = Eigen::Rotation2Dd(Xi.theta).toRotationMatrix();
    const Eigen::Matrix2d Riz = Eigen::Rotation2Dd(Xi.theta + Z.theta).toRotationMatrix();
    const Eigen::Matrix2d W = Riz * s.edge->information.topLeftCorner<2, 2>() * Riz.transpose();
    // t_j - t_i = R_i t_z; a fixed end's position moves into the constant.
    Eigen::Vector2d c = Ri * Eigen::Vector2d(Z.x, Z.y);
    const int a = layout.block[static_cast<std::size_t>(s.i)];
    const int b = layout.block[static_cast<std::size_t>(s.j)];
    if (a == kNoBlock) c += Eigen::Vector2d(Xi.x, Xi.y);
    if (b == kNoBlock) c -= Eigen::Vector2d(Xj.x, Xj.y);
    AddDifference<2>(a, b, W, c, &H, &rhs);
  }
  if (!SolveSparse(2 * layout.num_blocks, H, rhs, &t)) return false;
  for (std::size_t k = 0; k < layout.poses.size(); ++k) {
    const int a = layout.block[k];
    if (a == kNoBlock) continue;
    Pose2& x = *layout.poses[k];
    x = Pose2(t[2 * a], t[2 * a + 1], x.theta);
  }
  return true;
}

}  // namespace lifelong::slam::backend
