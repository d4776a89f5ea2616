// One ground-truth relation of Kümmerle et al. 2009 ("On measuring the accuracy of SLAM
// algorithms"): the true pose of the robot at t2 in the frame of the robot at t1. Read by
// io/relations.hpp, scored by eval/metrics/metrics.hpp.
#pragma once

#include "sensor/pose2.hpp"

namespace lifelong {

struct Relation {
  double t1_s = 0.0;  ///< s, log time of the first pose
  double t2_s = 0.0;  ///< s, log time of the second pose
  Pose2 T_1_2;        ///< pose at t2 in the frame of the pose at t1
};

}  // namespace lifelong
