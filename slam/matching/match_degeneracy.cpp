#include "slam/matching/match_degeneracy.hpp"

namespace lifelong::slam {

void TakeDegenerateDirectionFromGuess(const Pose2& guess, const Eigen::Matrix3d& odometry,
                                      const MatchResult& match, Pose2* X,
                                      Eigen::Matrix3d* information) {
  Eigen::Vector2d u(match.T_ref_rival.x - X->x, match.T_ref_rival.y - X->y);
  if (u.norm() < 1e-9) return;
  u.normalize();
  const double along = u.dot(Eigen::Vector2d(guess.x - X->x, guess.y - X->y));
  X->x += along * u.x();
  X->y += along * u.y();
  // B maps world (x, y, theta) to (along u, across u, theta); I' = B I B^T in those axes.
  Eigen::Matrix3d B = Eigen::Matrix3d::Identity();
  B.block<1, 2>(0, 0) = u.transpose();
  B.block<1, 2>(1, 0) << -u.y(), u.x();
  Eigen::Matrix3d I = B * *information * B.transpose();
  I.row(0).setZero();
  I.col(0).setZero();
  I(0, 0) = odometry(0, 0);  // isotropic in x and y
  *information = B.transpose() * I * B;
}

}  // namespace lifelong::slam
