// The observation stream from the simulator or a log into SLAM.
#pragma once

#include <optional>

#include "sensor/laser_scan.hpp"
#include "sensor/pose2.hpp"

namespace lifelong {

/// Wheel odometry: the robot pose in the (drifting) odometry frame.
struct Odometry {
  double stamp_s = 0.0;
  Pose2 T_odom_robot;
};

/// One laser scan with the odometry pose at its time, and the true pose when known
/// (simulation only; never consumed by slam).
struct Observation {
  double stamp_s = 0.0;
  Pose2 T_odom_robot;
  LaserScan scan;
  std::optional<Pose2> T_world_robot_true;
  /// The stream holds no odometry over the step from the previous observation to this one (a
  /// log that lost it): T_odom_robot repeats the previous observation's, and the mapper
  /// searches for the step instead of trusting it.
  bool odometry_lost = false;
};

}  // namespace lifelong
