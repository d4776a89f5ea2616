// The front end's sequential step (DESIGN.md data flow, step 2): a new node's scan matched
// against the local map of the last observed nodes' scans around the odometry guess. The local
// map is the front end's own: a node the back end removes stays in it until it ages out, so
// the front end costs and measures the same in every mode. The match gives
// the odometry edge's measurement and information; where it fails, or is weak and not distinct
// (WeakAndAmbiguous), the odometry alone does,
// and along a direction the match cannot tell (a corridor) the odometry does too
// (match_degeneracy.hpp).
#pragma once

#include <cstddef>
#include <deque>
#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "sensor/pose2.hpp"
#include "slam/graph/pose_graph.hpp"
#include "slam/matching/incremental_config.hpp"
#include "slam/matching/node_data.hpp"
#include "slam/matching/scan_matcher.hpp"

namespace lifelong::slam {

/// Information of the odometry fallback edge over `delta`, in the edge's error frame.
Eigen::Matrix3d OdometryInformation(const IncrementalConfig& c, const Pose2& delta);
/// Information of a lost step's fallback edge: within lost_window_m, any heading.
Eigen::Matrix3d LostStepInformation(const IncrementalConfig& c);

struct SequentialMatch {
  Pose2 X_new;                          ///< the new node's pose (the guess when not matched)
  Eigen::Matrix3d information;          ///< of the edge from the last node, in its error frame
  bool matched = false;                 ///< the match was good
  bool degenerate = false;              ///< ...but ambiguous along a direction the odometry gave
  bool weak = false;                    ///< refused: weak and not distinct (WeakAndAmbiguous)
  bool lost = false;                    ///< the step's odometry was lost: searched over a full turn
  bool recovered = false;               ///< matched by the second, wider search (recovery_window_m)
  std::size_t local_map_from_scan = 0;  ///< the stream index of the local map's oldest scan
};

/// Where node `id`'s scan (the stream's scan `scan_index`) lies at the current estimate: the
/// node's pose, or once the node is removed, wherever the node that inherited its scan holds it
/// (ScanStore).
using ScanPoseFn = std::function<Pose2(NodeId id, std::size_t scan_index)>;

class SequentialMatcher {
 public:
  explicit SequentialMatcher(const IncrementalConfig& config) : config_(config) {}

  /// Node `id`'s scan (the stream's scan `scan_index`; `points`, its thinned returns) joins
  /// the local map, whose oldest scan leaves once it holds local_map_nodes. Whether the
  /// node later leaves the graph does not matter here.
  void Remember(NodeId id, std::size_t scan_index, const LaserScan& scan,
                const std::vector<Eigen::Vector2d>& points);

  /// The oldest node whose scan is in the local map (none: empty).
  std::optional<NodeId> OldestRemembered() const {
    if (local_.empty()) return std::nullopt;
    return local_.front().id;
  }

  /// `points` (the new scan's, robot frame) matched against the local map, placed by
  /// `scan_pose`, around X_last * delta (delta: the odometry since the last node). When the
  /// odometry of the step was lost, over a full turn and lost_window_m around it.
  SequentialMatch Match(const ScanPoseFn& scan_pose, const Pose2& X_last, const Pose2& delta,
                        const std::vector<Eigen::Vector2d>& points, bool odometry_lost = false);

  /// A scan taken after the last node, `T_last_scan` from it by odometry (`points`: its
  /// thinned returns), refined against the table the last node was matched on, in that
  /// match's frame (IncrementalConfig::between_refine_m). Returns the refined T_last_scan, or
  /// nothing when refinement is off, the last node's step built no table, or the refined
  /// pose scores under matcher.min_score.
  std::optional<Pose2> RefineBetween(const std::vector<Eigen::Vector2d>& points,
                                     const Pose2& T_last_scan) const;

 private:
  struct LocalScan {
    NodeId id = 0;
    std::size_t scan_index = 0;
    /// Its return points, or its surfaces (SurfaceRule::JoinsAny), in the robot frame.
    std::vector<Eigen::Vector2d> reference;
  };
  /// The local map in the world frame.
  std::vector<Eigen::Vector2d> LocalMap(const ScanPoseFn& scan_pose) const;

  /// The match over `mc`'s window around `guess` (reference: the local map, uncropped).
  MatchResult Search(const std::vector<Eigen::Vector2d>& points, const Pose2& guess,
                     const MatcherConfig& mc, std::vector<Eigen::Vector2d> reference);
  /// A match strong and distinct enough to take from the recovery search; `guess_score`: the
  /// first search's best score around the odometry's guess (0 when it found nothing).
  bool Recovers(const MatchResult& match, double guess_score) const;

  SequentialMatch MatchStep(const ScanPoseFn& scan_pose, const Pose2& X_last, const Pose2& delta,
                            const std::vector<Eigen::Vector2d>& points, bool odometry_lost);

  IncrementalConfig config_;
  ReferenceGrid grid_;       ///< the matcher's table, rebuilt for each match
  bool grid_built_ = false;  ///< Search built grid_ during the current Match
  /// The last node's pose in grid_'s frame, when its step built grid_ (RefineBetween).
  std::optional<Pose2> grid_anchor_;
  std::deque<LocalScan> local_;  ///< the last local_map_nodes observed nodes' scans, oldest first
};

}  // namespace lifelong::slam
