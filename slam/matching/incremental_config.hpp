// The sequential (incremental) scan matcher's configuration: how each observation is matched
// against the local map of recent nodes, and what happens when the match fails or is
// degenerate. Read by the mapper, the scan store and the loop closer (its submap surfaces).
#pragma once

#include "slam/matching/scan_matcher.hpp"

namespace lifelong::slam {

/// The incremental matcher's window and acceptance (its table and field are the matcher's
/// defaults). Real odometry turns by more than a simulated one between observations, and the
/// mean likelihood of a match in a wide hall, whose returns lie far apart, is low: a 0.26 rad
/// window and a 0.5 score failed one match in three on acapulco and edmonton and bent csail
/// (docs/results.md "Sequential matching on real odometry"). The linear window stays 0.3 m: at
/// 0.5 m the matcher slips along the simulated corridors.
inline MatcherConfig IncrementalMatcherDefaults() {
  MatcherConfig m;
  m.angular_window_rad = 0.5;
  m.min_score = 0.3;
  return m;
}

/// A step whose odometry was lost is searched over a full turn (half-width pi).
inline constexpr double kLostStepWindowRad = 3.14159265358979323846;

struct IncrementalConfig {
  /// The last observations whose scans form the local map, removed from the graph or not: 60
  /// cover about 30 m of path. A longer memory holds the heading through wide halls whose
  /// scans see few walls (acapulco 0.301 -> 0.127 m); 8 (before 2026-12-04) could not hold it
  /// through a room, and 100 took wrong closures on two real logs (docs/results.md "The front
  /// end's local map: how long").
  int local_map_nodes = 60;
  double point_spacing_m = 0.05;  ///< voxel thinning of matched points
  /// The local map joins consecutive returns of a scan into surfaces (SurfacePoints), so its
  /// likelihood field is smooth along walls hit at grazing angles and motion along them is
  /// not under-measured. YAML keys surface_gap_m (0: return points, before 2026-12-02),
  /// surface_line_gap_m and surface_line_tol_m (the line rule; gap 0: off).
  SurfaceRule surfaces;
  MatcherConfig matcher = IncrementalMatcherDefaults();  ///< window around the odometry guess
  double odom_sigma_xy_m = 0.05;     ///< fallback edge when matching fails: base sigma
  double odom_sigma_xy_per_m = 0.1;  ///< ...plus this much per metre travelled
  double odom_sigma_rad = 0.02;      ///< ...heading base sigma
  double odom_sigma_rad_per_rad = 0.1;
  /// A match whose best distinct rival scores above this share of it does not measure the
  /// direction towards the rival: the odometry does (slam/matching/match_degeneracy.hpp). 1: off,
  /// the match alone (before 2026-12-04).
  double max_ambiguity = 0.95;
  /// A weak match (mean likelihood below weak_score) counts only when it is also distinct: its
  /// best distinct rival scores at most weak_max_ambiguity of it; otherwise the odometry gives
  /// the edge. A weak score is what a wide hall's sparse returns give (acapulco, edmonton: the
  /// reason min_score is 0.3), and there every rival stayed under 0.62 of the winner; where
  /// a scan sees little of the local map (turning in place into a room) a weak winner and a
  /// rival by 10-30 degrees score alike, and taking the winner turned freiburg-079 by 10-24
  /// degrees at a step (docs/results.md "Sequential matching on real odometry"). 0: off.
  double weak_score = 0.5;
  double weak_max_ambiguity = 0.7;
  /// A step whose odometry the stream lost (Observation::odometry_lost) is searched over a
  /// full turn and this half-width in x and y around the last pose; when that search fails,
  /// its edge says only that the robot stayed within this much and turned somehow.
  double lost_window_m = 1.0;
  /// A step whose match fails, or is refused as weak and not distinct, is searched again this
  /// far in x and y around the odometry guess (the same heading window). The match is taken
  /// only when it is neither weak nor close to a rival (score >= weak_score, ambiguity <=
  /// weak_max_ambiguity; but see recover_past_odometry): it departs from the odometry by more
  /// than the first window allows.
  /// It catches an odometry step wrong by more than the matcher's window: freiburg-079's
  /// odometry reads every reversing step as forward, twice the step (0.5-0.7 m) off. 0: off.
  double recovery_window_m = 1.5;
  /// A recovered match closer to its rival than weak_max_ambiguity is still taken when the
  /// first search, around the odometry's guess, scored below that rival: the odometry is then
  /// the least likely of the three places the step could go, and refusing the match hands the
  /// step to it. On freiburg-079 a recovered match at 0.93 (ambiguity 0.705, rival 0.65)
  /// against the odometry's 0.45 went to the odometry and bent the map by a metre
  /// (docs/results.md "Large real logs"). false: the odometry takes it (before 2026-12-06).
  bool recover_past_odometry = true;
  /// A scan taken between keyframes is placed by the odometry since the last node, then
  /// refined against the table the last node was matched on (RefinePose: continuous ascent of
  /// the match score, within this shift and turn of the odometry's pose); the refinement is
  /// kept when it scores matcher.min_score or more. The odometry's heading errs by about a
  /// degree over a keyframe step on the benchmark's raw logs, and every scan is a trajectory
  /// pose that relations and ATE read. Chosen on the raw aces, fr079 and mit-csail logs
  /// (0.1 / 0.05 and 0.3 / 0.2 measured too; docs/results.md "The benchmark's raw logs").
  /// 0 m: the odometry alone (before 2026-12-07).
  double between_refine_m = 0.2;
  double between_refine_rad = 0.1;  ///< ...and turn (rad)
};

/// The weak-match rule above: true when `match` (ok) is to be refused.
inline bool WeakAndAmbiguous(const MatchResult& match, const IncrementalConfig& config) {
  return match.score < config.weak_score && match.ambiguity > config.weak_max_ambiguity;
}

}  // namespace lifelong::slam
