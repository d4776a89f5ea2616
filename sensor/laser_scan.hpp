// A planar laser scan in its sensor frame, as logged by CARMEN (FLASER / ROBOTLASER1).
#pragma once

#include <cstddef>
#include <vector>

#include "sensor/pose2.hpp"

namespace lifelong {

struct LaserScan {
  double stamp_s = 0.0;              ///< s, time of the scan
  double angle_min_rad = 0.0;        ///< bearing of beam 0 in the laser frame
  double angle_increment_rad = 0.0;  ///< bearing step between beams
  double range_max_m = 81.83;        ///< readings >= this are "no return"
  Pose2 T_robot_laser;               ///< laser mount on the robot
  std::vector<float> ranges_m;       ///< one range per beam, m

  double Bearing(std::size_t i) const {
    return angle_min_rad + angle_increment_rad * static_cast<double>(i);
  }
  /// A beam is a valid return when it hit something closer than the maximum range.
  bool IsReturn(std::size_t i) const {
    return ranges_m[i] > 0.0f && ranges_m[i] < static_cast<float>(range_max_m);
  }
};

}  // namespace lifelong
