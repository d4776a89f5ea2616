// SE(2) maths for the back-end and marginalization, in Eigen. Poses are parametrized as
// (x, y, theta) with additive increments, as g2o's VertexSE2.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/LU>

#include "sensor/pose2.hpp"
#include "types/pose_factors.hpp"

namespace lifelong::slam {

inline Eigen::Vector3d T2V(const Pose2& p) { return {p.x, p.y, p.theta}; }
inline Pose2 V2T(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

/// Adjoint of SE(2) in (x, y, theta): T * v2t(d) * T^-1 = v2t(Ad(T) d) to first order, i.e.
/// T * exp(d) = exp(Ad(T) d) * T.
inline Eigen::Matrix3d Adjoint(const Pose2& T) {
  const double c = std::cos(T.theta), s = std::sin(T.theta);
  Eigen::Matrix3d ad;
  ad << c, -s, T.y, s, c, -T.x, 0.0, 0.0, 1.0;
  return ad;
}

/// The inverse of a 3x3 information or covariance, symmetrized and regularized by 1e-9 so a
/// singular one inverts to a very large (not an infinite) one.
inline Eigen::Matrix3d RegularizedInverse(const Eigen::Matrix3d& m) {
  Eigen::Matrix3d sym = 0.5 * (m + m.transpose());
  sym += 1e-9 * Eigen::Matrix3d::Identity();
  return sym.inverse();
}

/// Error of a relative-pose constraint (DESIGN.md):  e = t2v(Z^-1 * (Xi^-1 * Xj)),
/// with the angle normalized. Written out, with R(.) the 2D rotation:
///   e_t     = R(th_z)^T (R(th_i)^T (t_j - t_i) - t_z)
///   e_theta = th_j - th_i - th_z
inline Eigen::Vector3d RelativeError(const Pose2& Xi, const Pose2& Xj, const Pose2& Z) {
  return T2V(Z.Inverse() * (Xi.Inverse() * Xj));
}

/// The stacked errors of a clique factor (pose_graph.hpp): block j is RelativeError(X_r,
/// X_j, Z_j) for member j + 1, with `pose(u)` the pose of clique.nodes[u] (0: the root).
template <typename PoseOf>
Eigen::VectorXd CliqueError(const CliqueFactor& clique, PoseOf&& pose) {
  const Eigen::Index k = static_cast<Eigen::Index>(clique.nodes.size()) - 1;
  Eigen::VectorXd e(3 * k);
  const Pose2& Xr = pose(std::size_t{0});
  for (Eigen::Index j = 0; j < k; ++j) {
    const auto uj = static_cast<std::size_t>(j);
    e.segment<3>(3 * j) = RelativeError(Xr, pose(uj + 1), clique.T_root_node[uj]);
  }
  return e;
}

/// The chi2 of the relative-pose measurement Z between Xi and Xj under `information`:
/// e^T Omega e with e = RelativeError(Xi, Xj, Z).
inline double EdgeChi2(const Pose2& Xi, const Pose2& Xj, const Pose2& Z,
                       const Eigen::Matrix3d& information) {
  const Eigen::Vector3d e = RelativeError(Xi, Xj, Z);
  return e.dot(information * e);
}

/// Analytic Jacobians of RelativeError with respect to additive increments of Xi and Xj.
///   de_t/dt_i = -R_z^T R_i^T,  de_t/dth_i = R_z^T dR_i^T/dth (t_j - t_i),  de_th/dth_i = -1
///   de_t/dt_j =  R_z^T R_i^T,                                            de_th/dth_j = +1
inline void RelativeErrorJacobians(const Pose2& Xi, const Pose2& Xj, const Pose2& Z,
                                   Eigen::Matrix3d* J_i, Eigen::Matrix3d* J_j) {
  const double ci = std::cos(Xi.theta), si = std::sin(Xi.theta);
  const double cz = std::cos(Z.theta), sz = std::sin(Z.theta);
  Eigen::Matrix2d RiT;
  RiT << ci, si, -si, ci;
  Eigen::Matrix2d dRiT;
  dRiT << -si, ci, -ci, -si;
  Eigen::Matrix2d RzT;
  RzT << cz, sz, -sz, cz;
  const Eigen::Vector2d dt(Xj.x - Xi.x, Xj.y - Xi.y);
  J_i->setZero();
  J_j->setZero();
  J_i->block<2, 2>(0, 0) = -RzT * RiT;
  J_i->block<2, 1>(0, 2) = RzT * dRiT * dt;
  (*J_i)(2, 2) = -1.0;
  J_j->block<2, 2>(0, 0) = RzT * RiT;
  (*J_j)(2, 2) = 1.0;
}

}  // namespace lifelong::slam
