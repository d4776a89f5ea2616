// A sequential match that cannot tell its pose from a rival along one direction.
#pragma once

#include <Eigen/Core>

#include "sensor/pose2.hpp"
#include "slam/matching/scan_matcher.hpp"

namespace lifelong::slam {

/// Where the match cannot tell its pose from a rival one along a direction u (a corridor that
/// looks the same 0.3 m on: ambiguity near 1), the scan does not measure u. The position along u
/// is then the odometry guess's and the information along u the odometry's; heading and the
/// direction across u stay the match's (degeneracy of scan matching: Zhang, Kaess and Singh,
/// ICRA 2016). A rival by heading alone changes nothing.
/// X and information (world frame) are the match's on entry; odometry is the odometry edge's
/// information, isotropic in x and y.
void TakeDegenerateDirectionFromGuess(const Pose2& guess, const Eigen::Matrix3d& odometry,
                                      const MatchResult& match, Pose2* X,
                                      Eigen::Matrix3d* information);

}  // namespace lifelong::slam
