// Trajectory metrics against ground truth:
//  - ATE after the best rigid SE(2) alignment, closed form (Horn 1987 / Umeyama 1991
//    without scale, specialised to 2D: the rotation is atan2 of the summed cross and dot
//    products of the centred positions).
//  - RPE over a fixed index delta (Sturm et al. 2012, "A benchmark for RGB-D SLAM"):
//    E_i = (T_i^-1 T_{i+d})^-1 (P_i^-1 P_{i+d}), truth T, estimate P.
//  - The relations metric of Kuemmerle et al. 2009 ("On measuring the accuracy of SLAM
//    algorithms"): e_ij = Between(Between(x_i, x_j), delta*_ij), without interpolation.
//  - Loop-closure precision / recall against the true poses of the nodes.
#pragma once

#include <cstddef>
#include <vector>

#include "sensor/pose2.hpp"
#include "types/relation.hpp"
#include "types/stamped_pose.hpp"

#include "eval/metrics/types.hpp"

namespace lifelong::eval {

/// q-quantile (q in [0, 1]) with linear interpolation between order statistics (as
/// numpy's default); 0 for an empty vector.
double Percentile(std::vector<double> values, double q);

/// Closed-form rigid alignment T_truth_est minimising sum |T p_est_i - p_truth_i|^2
/// over positions. Empty input gives identity, one pose a pure translation.
/// Throws std::invalid_argument when the sizes differ.
Pose2 AlignSE2(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth);

struct AteResult {
  std::size_t count = 0;      ///< matched poses used
  double rmse_m = 0.0;        ///< m, RMSE of position errors after alignment
  double mean_m = 0.0;        ///< m
  double max_m = 0.0;         ///< m
  double rot_rmse_deg = 0.0;  ///< deg, RMSE of heading errors after alignment
  Pose2 T_truth_est;          ///< the alignment (pass it to the map blur)
};

/// ATE of poses matched by index (estimate[i] is the estimate of truth[i]).
AteResult ComputeAte(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth);

/// Pairs estimate/truth by stamp: for each estimate pose, the truth pose whose stamp is
/// nearest and within tolerance_s (no interpolation). Unmatched estimate poses are dropped.
struct MatchedPoses {
  std::vector<Pose2> estimate;
  std::vector<Pose2> truth;
  std::size_t unmatched = 0;
};
MatchedPoses MatchByStamp(const std::vector<StampedPose>& estimate,
                          const std::vector<StampedPose>& truth, double tolerance_s = 1e-3);

struct RpeResult {
  std::size_t count = 0;       ///< pairs (i, i + delta) used
  double trans_rmse_m = 0.0;   ///< m
  double trans_mean_m = 0.0;   ///< m
  double rot_rmse_deg = 0.0;   ///< deg
  double rot_mean_deg = 0.0;   ///< deg
  double trans_per_m = 0.0;    ///< m of error per m travelled (sum err / sum true path)
  double rot_deg_per_m = 0.0;  ///< deg of error per m travelled
};

/// RPE over index pairs (i, i + delta), poses matched by index. The true path length of
/// a pair is the sum of the true steps between i and i + delta.
RpeResult ComputeRpe(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth,
                     int delta = 1);

struct RelationsResult {
  std::size_t count = 0;      ///< relations whose both stamps matched a pose
  std::size_t unmatched = 0;  ///< relations not used (a stamp matched no pose)
  double trans_mean_m = 0.0;  ///< m, mean |translation of e_ij|
  double trans_std_m = 0.0;   ///< m, population standard deviation
  double rot_mean_deg = 0.0;  ///< deg, mean |rotation of e_ij|
  double rot_std_deg = 0.0;   ///< deg, population standard deviation
};

/// Kuemmerle et al. 2009 relations error. Each stamp is looked up as the estimate pose
/// with the nearest stamp within +-tolerance_s; there is no interpolation across poses.
RelationsResult ComputeRelationsError(const std::vector<StampedPose>& estimate,
                                      const std::vector<Relation>& relations,
                                      double tolerance_s = 1e-3);

/// An accepted loop closure between nodes i and j (indices into the true node poses)
/// with the front-end's relative pose T_i_j.
struct LoopClosure {
  int i = 0;
  int j = 0;
  Pose2 T_i_j;
};

struct LoopClosureConfig {
  double correct_trans_m = 0.3;   ///< m, closure correct when |t error| <= this ...
  double correct_rot_deg = 5.0;   ///< deg, ... and |rotation error| <= this
  double revisit_dist_m = 1.0;    ///< m, a revisit is a node this close to an old node ...
  double revisit_rot_deg = 30.0;  ///< deg, ... with headings this close ...
  int min_index_gap = 50;         ///< ... that is at least this many nodes older
};

struct LoopClosureResult {
  int accepted = 0;                  ///< closures given
  int correct = 0;                   ///< closures within tolerance of the true relative pose
  int revisit_nodes = 0;             ///< nodes that are revisits by the definition above
  int recalled_nodes = 0;            ///< revisit nodes with >= 1 correct closure to an old node
  double precision = 0.0;            ///< correct / accepted; meaningful only when accepted > 0
  double recall = 0.0;               ///< recalled / revisit; meaningful only when revisit_nodes > 0
  std::vector<bool> correct_each;    ///< per closure, in the order given
  std::vector<double> error_m_each;  ///< per closure: translation error, m
  std::vector<double> error_deg_each;  ///< per closure: rotation error, deg
  std::vector<bool> revisit_each;      ///< per node: a revisit by the definition above
  std::vector<bool> recalled_each;     ///< per node: a revisit with a correct closure
};

/// Precision = share of accepted closures that are correct. Recall = share of revisit
/// nodes having at least one correct closure to a node at least min_index_gap older (at
/// any distance: a correct closure found at 1.5 m still counts). O(n^2) in the nodes.
LoopClosureResult ComputeLoopClosureStats(const std::vector<LoopClosure>& closures,
                                          const std::vector<Pose2>& true_nodes,
                                          const LoopClosureConfig& config = {});

/// Cumulative loop precision and recall at each observation of a run's timeline, from the
/// truth of its closures (`truth.correct_each`, in the order the mapper accepted them) and
/// of its nodes (one per row). A closure counts from the row whose `loop_closures` first
/// includes it, that is from the observation that accepted it, whatever the stamps.
std::vector<LoopCurvePoint> LoopCurve(const std::vector<TimelineRow>& timeline,
                                      const LoopClosureResult& truth);

/// Whether a curve can be drawn against time: its stamps never go back and end later than
/// they start (a log whose scans share one stamp's cannot). A curve of under two points can.
bool StampsAdvance(const std::vector<LoopCurvePoint>& curve);

}  // namespace lifelong::eval
