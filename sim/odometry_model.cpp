#include "sim/odometry_model.hpp"

#include <cmath>

namespace lifelong::sim {

Pose2 IntegrateWheels(const Pose2& pose, const WheelMotion& m, double track_width_m) {
  const double ds = 0.5 * (m.left_m + m.right_m);
  const double dtheta = (m.right_m - m.left_m) / track_width_m;
  const double heading = pose.theta + 0.5 * dtheta;
  return {pose.x + ds * std::cos(heading), pose.y + ds * std::sin(heading), pose.theta + dtheta};
}

WheelOdometry::WheelOdometry(const OdometryConfig& config, double true_track_width_m,
                             const Pose2& start)
    : config_(config), track_width_m_(true_track_width_m * config.track_scale), pose_(start) {}

void WheelOdometry::Update(const WheelMotion& true_motion, std::mt19937_64* rng) {
  const double k = config_.slip_variance_m2_per_m;
  WheelMotion measured = true_motion;
  measured.left_m = true_motion.left_m * config_.left_scale;
  measured.right_m = true_motion.right_m * config_.right_scale;
  if (k > 0.0) {
    measured.left_m += std::sqrt(k * std::abs(true_motion.left_m)) * Gaussian(rng);
    measured.right_m += std::sqrt(k * std::abs(true_motion.right_m)) * Gaussian(rng);
  }
  pose_ = IntegrateWheels(pose_, measured, track_width_m_);
}

}  // namespace lifelong::sim
