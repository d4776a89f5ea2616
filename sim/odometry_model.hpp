// Differential-drive kinematics and wheel-odometry error. Error model after Borenstein &
// Feng (1996, UMBmark): systematic errors (unequal wheel radii -> per-wheel scale, uncertain
// wheelbase -> track-width scale) and non-systematic slip, here a zero-mean Gaussian per
// wheel whose variance grows linearly with the distance that wheel rolled. Odometry is
// integrated from the noisy wheel travel, so its error accumulates like a real robot's.
#pragma once

#include <random>

#include "sensor/pose2.hpp"
#include "sim/random_streams.hpp"
#include "sim/scenario.hpp"

namespace lifelong::sim {

/// Travel of each wheel over one step, m (signed).
struct WheelMotion {
  double left_m = 0.0;
  double right_m = 0.0;
};

/// Pose after wheel travel on track width b (midpoint rule):
/// ds = (l + r) / 2, dtheta = (r - l) / b, x += ds cos(theta + dtheta / 2), ...
Pose2 IntegrateWheels(const Pose2& pose, const WheelMotion& m, double track_width_m);

class WheelOdometry {
 public:
  WheelOdometry(const OdometryConfig& config, double true_track_width_m, const Pose2& start);
  /// Integrates one step of true wheel travel as the encoders measure it. With slip, draws
  /// two Gaussians from `rng` whatever the motion (none without slip), so the noise of the
  /// t-th step depends only on the stream and t.
  void Update(const WheelMotion& true_motion, std::mt19937_64* rng);
  const Pose2& pose() const { return pose_; }

 private:
  OdometryConfig config_;
  double track_width_m_;  ///< as odometry assumes it
  Pose2 pose_;
};

}  // namespace lifelong::sim
