// A pose with its time: one line of a TUM trajectory (io), one pose of an estimate or of the
// ground truth (eval).
#pragma once

#include "sensor/pose2.hpp"

namespace lifelong {

struct StampedPose {
  double stamp_s = 0.0;  ///< s
  Pose2 T_world_robot;
};

}  // namespace lifelong
