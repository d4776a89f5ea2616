// Plain data exchanged between the experiment runner and the eval functions. Nothing
// here knows the simulator or the mapper: callers copy their records into these. The
// plain types other modules share too (Segment, StampedPose, ...) are in types/.
#pragma once

#include <cstddef>

#include "types/stage_times.hpp"

namespace lifelong::eval {

/// Loop closing against the truth up to an observation of the run: cumulative precision of
/// the closures accepted so far and recall of the revisits so far.
struct LoopCurvePoint {
  double t_s = 0.0;        ///< s, the observation's stamp
  double precision = 0.0;  ///< meaningful once accepted > 0
  double recall = 0.0;     ///< meaningful once revisits > 0
  int accepted = 0;
  int revisits = 0;
  int obs = 0;  ///< the observation, 0-based (the x axis when stamps do not advance)
};

/// One row of `<mode>/timeline.csv` (DESIGN.md output contract), one per observation.
struct TimelineRow {
  int obs = 0;                  ///< observation index, 0-based
  double t_s = 0.0;             ///< s, stamp of the observation
  double time_ms = 0.0;         ///< ms of mapper time spent on this observation
  int nodes = 0;                ///< graph nodes after the observation
  int edges = 0;                ///< graph edges (cliques as m(m-1)/2 pairs)
  double gamma = 0.0;           ///< e / (v (v - 1) / 2)
  double rss_mb = 0.0;          ///< MB, resident set size of the process
  std::size_t graph_bytes = 0;  ///< bytes held by the graph
  int loop_closures = 0;        ///< loop closures accepted so far (cumulative)
  double optimize_ms = 0.0;     ///< ms of time_ms spent optimizing and updating the map
  int nodes_removed = 0;        ///< nodes removed so far (cumulative)
  StageTimes stages;            ///< time_ms by stage (slam::StepStats::stages)
  /// How the observation's sequential edge came about: "first" (nothing to match),
  /// "matched", "degenerate" (matched; the odometry along one direction), "weak" (refused:
  /// weak and not distinct) or "odometry" (the match failed)
  const char* sequential = "first";
  bool odometry_lost = false;  ///< the step's odometry was lost (searched over a full turn)
};

}  // namespace lifelong::eval
