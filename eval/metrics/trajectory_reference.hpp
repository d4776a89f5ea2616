// Scoring a trajectory against a reference trajectory (a log's corrected poses, another
// system's output, the simulator's truth): the reference is interpolated at the estimate's
// stamps, then
//  - ATE after the best rigid SE(2) alignment (eval/metrics/metrics.hpp), and
//  - RPE over a fixed travelled distance (Geiger et al. 2012, KITTI odometry; Sturm et al.
//    2012): for each pose i, j is the first pose at least distance_m further along the
//    reference path, E_i = (R_i^-1 R_j)^-1 (P_i^-1 P_j), reference R, estimate P.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "sensor/pose2.hpp"
#include "types/stamped_pose.hpp"

namespace lifelong::eval {

/// Reference poses at the estimate's stamps: linear in position, shortest arc in heading,
/// between the two reference poses around each stamp when they are at most max_gap_s apart
/// (or the one reference pose within tolerance_s of it). Estimate poses with neither are
/// dropped and counted in `unmatched`.
struct ReferencePairs {
  std::vector<Pose2> estimate;
  std::vector<Pose2> reference;
  std::vector<std::size_t> index;  ///< of each pair's pose in the estimate
  std::size_t unmatched = 0;
};
ReferencePairs PairWithReference(const std::vector<StampedPose>& estimate,
                                 const std::vector<StampedPose>& reference, double max_gap_s = 0.5,
                                 double tolerance_s = 1e-3);

/// The same pairs when reference[i] is the pose of the estimate's scan i (a corrected log's own
/// poses), whatever the stamps say; PairWithReference by stamp when the sizes differ.
ReferencePairs PairScanByScan(const std::vector<StampedPose>& estimate,
                              const std::vector<StampedPose>& reference);

struct DistanceRpe {
  std::size_t count = 0;      ///< pairs (i, j) used
  double trans_rmse_m = 0.0;  ///< m
  double rot_rmse_deg = 0.0;  ///< deg
};
/// RPE over pairs distance_m apart along the reference path; poses matched by index. Pose j
/// pairs with pose i when it is the first at least distance_m - kRpeDistanceTolerance_m along:
/// a simulated robot at constant speed covers exactly distance_m in whole steps, and without
/// the tolerance the rounding of a trajectory file (6 decimals) flipped which pose each pair
/// took, so `score` read RPE 2 % off `run`'s own. No pair (a path shorter than distance_m):
/// count 0.
inline constexpr double kRpeDistanceTolerance_m = 1e-3;
DistanceRpe ComputeRpeAtDistance(const std::vector<Pose2>& estimate,
                                 const std::vector<Pose2>& reference, double distance_m = 1.0);

}  // namespace lifelong::eval
