// Sub-cell refinement of a correlative match. The lattice search (scan_matcher.hpp) returns a
// pose on a grid of resolution_m x resolution_m x angular step; the true pose lies within half
// a step of it. As Cartographer's Ceres scan matcher does after its correlative search (Hess
// et al. 2016, §V-B), the pose is then moved continuously, here to maximize the score itself,
//   S(x) = sum_i v(T(x) p_i),
// v the likelihood field interpolated bicubically between cell centres (C1). The step is
// damped ascent, (J^T J + mu D) dx = grad S, with J the Jacobian of v(T p_i),
//   d v_i / d(x, y, theta) = grad v^T [I | R'(theta) p_i],
// Gauss-Newton's matrix for the residuals 1 - v_i as the metric. Gauss-Newton on
// sum (1 - v_i)^2 itself was tried and dropped: points the reference never saw (v ~ 0) pull
// its minimum 1-2 cm off the truth on clean synthetic scans, where S's maximum is within
// millimetres. A step is kept only if it raises S (else mu grows, Levenberg-Marquardt); the
// pose never leaves the box of one lattice step around the start (a refinement, not a search).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "sensor/pose2.hpp"

namespace lifelong::slam {

class ReferenceGrid;

struct RefinedPose {
  Pose2 T_ref_cur;
  double start_score = 0.0;  ///< interpolated mean v at the start
  double score = 0.0;        ///< interpolated mean v at the result (>= start_score)
  int iterations = 0;        ///< Gauss-Newton steps taken
};

/// Refines `start` within |dx|, |dy| <= max_shift_m and |dtheta| <= max_turn_rad.
RefinedPose RefinePose(const ReferenceGrid& ref, const std::vector<Eigen::Vector2d>& points_in_cur,
                       const Pose2& start, double max_shift_m, double max_turn_rad);

}  // namespace lifelong::slam
