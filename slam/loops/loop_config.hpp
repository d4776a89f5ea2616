// The loop closer's configuration: where it searches (the local window from the projected
// uncertainty, the global place search), what it accepts, and how it verifies.
#pragma once

#include "slam/loops/loop_verifier.hpp"
#include "slam/loops/place_descriptor.hpp"
#include "slam/matching/scan_matcher.hpp"

namespace lifelong::slam {

/// Global loop closing (slam/loops/loop_closer_global.cpp): where the local search, gated by the
/// projected uncertainty, finds nothing, the node's place descriptor (Scan Context,
/// slam/loops/place_descriptor.hpp) proposes the most similar earlier places wherever the estimate
/// puts them; each is matched in a wide window around the heading the descriptor gives, and
/// goes through the same acceptance and group verification as a local closure. On by default
/// since 2026-12-04: it closes the campus (19.7 -> 0.69 m) and leaves the other real logs, raw
/// Intel and the twins' precision as they were (docs/results.md "The global loop search").
struct GlobalLoopConfig {
  bool enabled = true;
  int every = 5;  ///< observations between searches (when no local closure)
  /// ...and only after this much travel (m, odometry) since the last accepted closure: where
  /// closures keep coming, the local search holds the estimate and a search by place costs
  /// time for nothing (office_5min: 1.38x the whole process at 0).
  double after_m = 20.0;
  int candidates = 3;          ///< places matched per search, most similar first
  int index_neighbours = 100;  ///< ring-key neighbours compared in full per search
  double max_distance = 0.5;   ///< descriptor distance in [0, 1]: farther is no candidate
  int min_occupied = 30;       ///< descriptor bins: sparser places are neither indexed nor searched
  int context_nodes = 10;      ///< recent nodes whose points, with the node's, make its place
  /// A search also describes the query from origins this far to each side (m)...
  double lateral_step_m = 1.0;
  int lateral_steps = 2;            ///< ...this many on each side (0: from the robot only)
  double linear_window_m = 4.0;     ///< m, search half-width around the candidate's position
  double angular_window_rad = 0.2;  ///< rad, around the descriptor's heading
  /// A candidate the scan matches under loops.min_score against it and its graph neighbours
  /// is matched again: the scan's returns within near_range_m of the robot (0: never) against
  /// the old nodes within submap_travel_m of odometry travel of the candidate, before and
  /// after (its visit). Both for a place driven the other way: the laser then sees what the
  /// first pass saw before it reached the candidate, not what it saw there, and its far
  /// returns fall on ground the old scans saw only from elsewhere; returns beyond 12 m are
  /// also sparse and meet walls at grazing angles (grid.max_hit_range_m leaves them out of the
  /// map for that reason). The whole scan goes first: outdoors its far returns are the
  /// structure there is.
  double submap_travel_m = 20.0;  ///< m of travel each side of the candidate: its visit
  double near_range_m = 12.0;     ///< m from the robot: the returns matched again
  /// m of travel after a place's closure is proposed and waits for confirmation, during which
  /// every observation's scan is matched where that closure puts the robot (0: never;
  /// loop_closer_follow.cpp).
  double follow_m = 10.0;
  /// A match within reach of the covariance projection must pass the local search's
  /// consistency gate (consistency_chi2) against that covariance scaled by this squared: 1 is
  /// the local search's test. At 3 (before 2026-12-04) the next aisle of the simulated
  /// warehouse, 7.6 m off, passed on one seed in three.
  double plausible_sigmas = 1.0;
  PlaceDescriptorConfig descriptor;
};

/// The loop closer's matcher: a finer table and a wider likelihood field than the
/// incremental one's (its windows are set per attempt).
inline MatcherConfig LoopMatcherDefaults() {
  MatcherConfig m;
  m.resolution_m = 0.05;
  m.sigma_m = 0.08;
  return m;
}

struct LoopClosingConfig {
  bool enabled = true;
  double min_path_separation_m = 6.0;  ///< nodes closer along the graph are not candidates
  double overlap_radius_m = 1.0;       ///< sensor overlap added to the position uncertainty
  double gate_chi2 = 5.99;             ///< 95 % gate (2 dof) of the candidate test
  double max_position_sigma_m = 20.0;  ///< Dijkstra projection stops beyond this
  double min_window_m = 0.3;           ///< search window: 3 sigma, clamped to [min, max]
  double max_window_m = 6.0;
  double min_window_rad = 0.15;
  double max_window_rad = 0.5;
  /// Candidates whose position uncertainty (3 sigma) exceeds max_window_m are searched, in
  /// the clamped window, at every this many observations (and at every one while hypotheses
  /// wait for confirmation); in between, an observation searches only the candidates its
  /// windows cover. 1: at every observation; 0: never. The pruned graph projects wider
  /// uncertainties than the full one, so most of pruned's searches grow to the largest
  /// window: 5 makes pruned's loop closing cheaper than standard's on freiburg-079, but
  /// loses closures on logs it was not tuned on (acapulco, the infinite corridor), so the
  /// default stays 1 (docs/results.md "Loop closing's cost by mode").
  int beyond_window_every = 1;
  int neighbours_per_candidate = 2;  ///< graph neighbours of each candidate in the submap
  /// The submap is made of its nodes' surfaces, by the incremental matcher's rule
  /// (IncrementalConfig::surfaces), rather than of their return points (false before
  /// 2026-12-02).
  bool surfaces = true;
  /// ...joined along lines as well (SurfaceRule::line_gap_m), or by the gap alone.
  bool surface_lines = true;
  /// The submap holds one visit: candidates observed within this many observations of the
  /// most likely candidate (and their neighbours alike). 0: every candidate.
  int submap_span = 0;
  double min_score = 0.6;       ///< a good match...
  double max_ambiguity = 0.85;  ///< ...and an unambiguous one...
  /// ...and a locally unique one: no pose uniqueness_radius_m away (8 directions, same
  /// heading) scores above max_flatness times the best. 1: off.
  double max_flatness = 0.9;
  double uniqueness_radius_m = 0.25;
  /// ...and, when a distinct rival scored at least context_ambiguity of it, one the robot's
  /// approach agrees with: the scans of the last context_span_m of travel, placed by the
  /// sequential estimate, must score at the match's pose at least as well as at the rival's
  /// against the older nodes' scans there. One scan in an aisle or a corridor sees the
  /// shelves or walls that every aisle shows; the way in (a cross aisle, a door) tells them
  /// apart. 1: off. 0.6 since 2026-12-05 (docs/results.md "Loop-closing settings measured").
  double context_ambiguity = 0.6;
  double context_span_m = 8.0;
  /// The edge is measured against the attached node's scan alone, in this window around
  /// the submap's answer (0: the submap match is the edge).
  double refine_window_m = 0.0;
  double refine_window_rad = 0.05;
  double consistency_chi2 = 16.27;  ///< 99.9 % gate (3 dof) of the correction
  int min_reference_points = 60;    ///< submap points the search can reach, fewer: no match
  /// A search that finds no pose above min_score still finds its best pose, for the score
  /// column of loop_attempts.csv. false: the branch and bound never opens a block that
  /// cannot beat min_score (MatcherConfig::cut_below_min_score), so a refused search costs a
  /// fraction and its score is left empty. One that finds a pose at min_score or above is
  /// searched again in full, so every closure, and the trajectory, is the same either way.
  /// Before 2026-12-06: always measured.
  bool measure_low_scores = false;
  MatcherConfig matcher = LoopMatcherDefaults();  ///< windows are set per attempt
  double optimize_edge_chi2 = 9.0;  ///< optimize at once when the new edge's chi2 exceeds
  int optimize_every = 10;          ///< ...and at least every this many closures
  /// Group verification: a closure enters the graph only once enough others confirm it
  /// (slam/loops/loop_verifier.hpp).
  LoopVerifierConfig verify;
  /// A loop edge whose chi2 at the estimate exceeds this is suspect (its robust kernel is
  /// switching it off): its nodes are neither removed nor sparsified, so that no
  /// marginal bakes it in.
  double suspect_chi2 = 16.27;
  GlobalLoopConfig global;
};

}  // namespace lifelong::slam
