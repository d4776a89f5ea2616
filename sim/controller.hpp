// Waypoint-following for a differential drive: turn toward the next waypoint (in place
// when the heading error is large), drive with acceleration limits, and brake along
// v = sqrt(2 a d) so the robot slows down near the waypoint.
#pragma once

#include "sensor/pose2.hpp"
#include "sim/geometry.hpp"
#include "sim/scenario.hpp"

namespace lifelong::sim {

struct DriveCommand {
  double v_mps = 0.0;    ///< forward speed
  double w_radps = 0.0;  ///< yaw rate
};

class WaypointController {
 public:
  explicit WaypointController(const RobotConfig& robot) : robot_(robot) {}

  /// True when `pose` is within the waypoint tolerance of `target`.
  bool Reached(const Pose2& pose, const Point& target) const;
  /// Next command toward `target` from the current command, one step of dt_s.
  DriveCommand Toward(const Pose2& pose, const Point& target, const DriveCommand& current,
                      double dt_s) const;
  /// Next command braking to a standstill.
  DriveCommand Brake(const DriveCommand& current, double dt_s) const;

 private:
  DriveCommand Limit(const DriveCommand& wanted, const DriveCommand& current, double dt_s) const;
  RobotConfig robot_;
};

}  // namespace lifelong::sim
