// `lifelong score` (issue #33): any system's trajectory, and optionally its map, scored on a
// simulated run or a log with the figures a mode of `run` or `replay` gets. The truth comes
// from a run's directory (its truth/), a truth directory, a simulated log (its
// LOG-stem.truth.* files) or a corrected CARMEN log (its FLASER poses: ATE and RPE only).
// Poses are paired with the truth by stamp (a corrected log's: scan by scan); a map is
// aligned by the trajectory's ATE alignment, as a mode's is.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "eval/experiment/experiment.hpp"
#include "eval/metrics/summary.hpp"
#include "types/occupancy_grid.hpp"
#include "types/stamped_pose.hpp"

namespace lifelong::eval {

struct ScoreTruth {
  std::string source;                   ///< the path given
  std::string kind;                     ///< "run", "truth", "simulated log" or "corrected log"
  std::vector<StampedPose> trajectory;  ///< true poses, or the log's reference poses
  bool per_scan = false;                ///< pair scan by scan (a corrected log's own poses)
  std::optional<GroundTruth> walls;     ///< the true walls (simulated truth only)
  /// A corrected log's scans (scan_cells: the system's map of them against the reference's).
  std::vector<Observation> scans;
  /// A simulated log's scans with their true poses, given its scenario (walls->world set):
  /// what the robot saw of each changing object (change_recall).
  std::vector<Observation> stream;
};

/// Throws InputError naming the path when it is none of the four. With `scenario` (a
/// simulated log's only), the world's doors and boxes too, for change_recall; InputError
/// naming the scenario when its world's changes are not those of the log's truth files.
ScoreTruth LoadScoreTruth(const std::string& path, const std::string& scenario = "");

struct ScoredSystem {
  std::string name;
  std::vector<StampedPose> trajectory;
  std::optional<OccupancyGrid> map;
};

struct SystemScore {
  ModeSummary summary;         ///< ate_rmse_m, rpe_1m, reference_matched, blur, ...
  std::vector<Pose2> aligned;  ///< the matched poses, in the truth frame (for figures)
  std::vector<Pose2> truth;    ///< their true poses
};

/// The system's figures against the truth; with a scenario's world and a map also change_recall
/// and stale_seen_cells, as `run` scores a mode; on a corrected log also scan_cells at the default
/// grid (its scans at the system's poses, interpolated at their stamps or taken scan by scan
/// when it has one pose a scan, against the same scans at the log's poses). Throws InputError
/// naming the system when none of its poses pairs with the truth.
SystemScore ScoreSystem(const ScoreTruth& truth, const ScoredSystem& system);

}  // namespace lifelong::eval
