// What the Mapper reports: per observation (StepStats) and per event (an accepted closure, a
// marginalization, an edge-budget sparsification). Plain data, read by eval.
#pragma once

#include <cstddef>
#include <vector>

#include "sensor/pose2.hpp"
#include "slam/graph/pose_graph.hpp"
#include "slam/loops/loop_attempt.hpp"
#include "types/stage_times.hpp"

namespace lifelong::slam {

/// What one call of AddObservation did. Reported through the hook and the return value.
struct StepStats {
  int scan_index = 0;          ///< index of the scan in the stream, 0-based
  int observation_index = -1;  ///< index of the observation (keyframe), -1 if not one
  double stamp_s = 0.0;
  double time_ms = 0.0;  ///< wall time spent in AddObservation
  std::size_t nodes = 0;
  std::size_t edges = 0;  ///< as for gamma (cliques count their pairs)
  double gamma = 0.0;
  std::size_t graph_bytes = 0;
  int loop_closures_total = 0;
  int nodes_removed_total = 0;
  bool incremental_match_ok = false;
  /// ...and ambiguous along a direction, which the odometry measured (max_ambiguity)
  bool incremental_match_degenerate = false;
  /// ...or refused, weak and not distinct (incremental weak_score, weak_max_ambiguity)
  bool incremental_match_weak = false;
  /// ...matched by the wider second search (incremental recovery_window_m)
  bool incremental_match_recovered = false;
  /// The stream index of the oldest scan the step was matched against (the front end's local
  /// map: the last incremental local_map_nodes observed nodes, whether or not pruned since)
  std::size_t local_map_from_scan = 0;
  /// The step's odometry was lost (Observation::odometry_lost): searched over a full turn
  bool odometry_lost = false;
  bool loop_closed = false;
  bool optimized = false;
  double optimize_ms = 0.0;  ///< part of time_ms spent in the back-end and the map update
  bool map_synced = false;   ///< the map re-rendered the scans the estimate moved
  StageTimes stages;         ///< time_ms by stage
  int optimizer_iterations = 0;
  std::vector<LoopAttempt> loop_attempts;  ///< the loop searches that had candidates
};

/// An accepted loop closure: current node, older node, and the measured T_old_cur.
struct LoopClosureRecord {
  NodeId current = 0;
  NodeId old = 0;
  double stamp_current_s = 0.0;
  double stamp_old_s = 0.0;
  Pose2 T_old_current;
  bool injected = false;  ///< a deliberately wrong closure (the hypothesis hook's)
};

/// One marginalization: which node, its clique size and the KL divergence (nats).
struct MarginalizationRecord {
  NodeId node = 0;
  std::size_t clique_size = 0;
  double kl_divergence = 0.0;
  double information_gain_bits = 0.0;
};

/// One edge-budget sparsification (PruningConfig::max_edges_per_node): the pose edges among a
/// node and its neighbours replaced by their Chow-Liu tree.
struct SparsificationRecord {
  NodeId centre = 0;             ///< the node whose Markov blanket was sparsified
  std::size_t nodes = 0;         ///< the centre and its neighbours
  std::size_t edges_before = 0;  ///< pose edges among them before...
  std::size_t edges_after = 0;   ///< ...and after (nodes - 1)
  double kl_divergence = 0.0;    ///< nats, KL(joint of the old edges || tree)
};

}  // namespace lifelong::slam
