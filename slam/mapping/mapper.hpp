// The mapper facade: consumes the observation stream (simulated or from a log), builds the
// pose graph (incremental scan matching, loop closing), optimizes it, keeps the counting grid
// map in step with the graph, and, in the pruned modes, removes the nodes whose scans carry no
// information (seed §5.1) by marginalizing them (seed §5.3-5.5).
//
// Per observation (AddObservation):
//  1. keyframe test on odometry; a scan that is not a keyframe is only anchored to a node;
//  2. incremental match against the local map of recent node scans -> sequential edge;
//  3. loop closing: Dijkstra projection, candidate gate, wide-window match, checks;
//  4. optimization after loop closures, then the map follows the graph (MoveScan);
//  5. pruning: information gains near the current node, remove while <= threshold.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "sensor/observation.hpp"
#include "slam/graph/pose_graph.hpp"
#include "slam/grid/grid_map.hpp"
#include "slam/loops/loop_attempt.hpp"
#include "slam/mapping/mapper_config.hpp"
#include "types/stage_times.hpp"
#include "types/stamped_pose.hpp"

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

class Mapper {
 public:
  explicit Mapper(const MapperConfig& config);
  ~Mapper();
  Mapper(const Mapper&) = delete;
  Mapper& operator=(const Mapper&) = delete;

  StepStats AddObservation(const Observation& observation);

  /// Final optimization and map refresh (call once at the end of the stream).
  void Finish();

  const PoseGraph& graph() const;
  const Values& values() const;
  const GridMap& map() const;
  /// A pose for every scan seen so far, in stream order (removed nodes' scans included,
  /// held relative to a surviving node).
  std::vector<StampedPose> Trajectory() const;
  /// The pose of the latest scan (as Trajectory().back(), without building the whole list).
  StampedPose LastScanPose() const;
  const std::vector<LoopClosureRecord>& loop_closures() const;
  /// For each of loop_closures(): its edge's chi2 e^T Omega e at the current estimate, or
  /// nullopt when the edge is no longer in the graph (marginalized). Above
  /// loops.suspect_chi2 the back-end's kernel is switching it off.
  std::vector<std::optional<double>> LoopEdgeChi2() const;
  /// Accepted closures whose edge's chi2 exceeds loops.suspect_chi2: the robust kernel is
  /// switching them off, and their nodes are neither removed nor sparsified.
  int SuspectLoopEdges() const;
  /// Counts of the loop-closure verification (proposed, accepted, rejected, ...).
  const LoopVerifierStats& loop_verification() const;
  const std::vector<MarginalizationRecord>& marginalizations() const;
  const std::vector<SparsificationRecord>& sparsifications() const;
  int observations() const;
  /// Beams the removal policy cut in the map (pruning.policy dpg, BeamCut), in all.
  std::size_t cut_beams() const;
  /// Self-check of the pruned modes' remembered information gains: the largest difference
  /// (bits) between a remembered gain that would be reused (valid, and no pending map change
  /// overlaps its scan) and the gain computed afresh from the map now. 0 when the
  /// bookkeeping is right (or nothing is remembered).
  double MaxGainCacheError() const;

  /// Called after every AddObservation that took an observation (keyframe).
  std::function<void(const StepStats&)> on_observation;
  /// Called with every loop-closure hypothesis before verification (eval's false-closure
  /// test moves some of them).
  void set_hypothesis_hook(std::function<void(LoopHypothesis*, const Values&)> hook);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace lifelong::slam
