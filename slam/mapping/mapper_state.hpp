// Internal state of the Mapper, shared by mapper.cpp, mapper_loops.cpp and pruning.cpp.
// Not part of the public API.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <vector>

#include <Eigen/Core>

#include "slam/graph/dijkstra.hpp"
#include "slam/graph/pose_graph.hpp"
#include "slam/grid/grid_map.hpp"
#include "slam/loops/loop_closer.hpp"
#include "slam/mapping/map_keeper.hpp"
#include "slam/mapping/mapper.hpp"
#include "slam/mapping/pruner.hpp"
#include "slam/mapping/scan_store.hpp"
#include "slam/mapping/scoped_ms.hpp"
#include "slam/matching/node_data.hpp"
#include "slam/matching/scan_matcher.hpp"
#include "slam/matching/sequential_matcher.hpp"
#include "slam/removal/removal_policy.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {

struct Mapper::State {
  /// std::invalid_argument when the config is invalid (Validate) or names an unknown policy
  /// or sparsifier.
  explicit State(const MapperConfig& c);

  MapperConfig config;
  LoopCloser closer;
  std::vector<LoopClosureRecord> loops;  ///< closures put into the graph, in order
  int since_optimize = 0;                ///< closures added since the last optimization
  double closed_at_m = 0.0;      ///< robot path length (odometry) at the last accepted closure
  int since_sync = 0;            ///< closures added since the map was last re-rendered (SyncMap)
  std::optional<Pruner> pruner;  ///< in the pruned modes: which node goes, what replaces it
  PoseGraph graph;
  Values values;
  MapKeeper keeper;  ///< the grid, and in the pruned modes the scans' information gains
  NodeStore nodes;
  std::vector<NodeId> recent;  ///< node ids in insertion order (surviving ones)
  ScanStore scans;             ///< every scan of the stream, on the node that anchors it
  NodeId next_id = 0;
  int observations = 0;
  StepStats* step = nullptr;            ///< stats of the observation being processed
  ScopedMs* innermost_timer = nullptr;  ///< of the stage timers running
  bool have_last = false;
  NodeId last_node = 0;
  SequentialMatcher sequential;  ///< the front end: each node against the local map
  /// Times its scope as the stage `field` of the observation being processed (none when
  /// there is none).
  ScopedMs Stage(double StageTimes::*field) {
    return ScopedMs(step ? &(step->stages.*field) : nullptr, &innermost_timer);
  }

  void AddSequentialNode(const Observation& obs, StepStats* stats);
  /// A scan taken between keyframes: held by the last node (ScanStore::AddPending), placed by
  /// odometry or, with incremental.between_refine_m, refined against the local map.
  void AddBetweenScan(const Observation& obs, const Pose2& delta);
  /// The odometry edge last_node -> id: `points` matched against the local map around the
  /// odometry guess X_last * delta (the odometry alone when the match fails; the odometry along
  /// a degenerate direction; a lost step is searched over a full turn). *X_new: the new
  /// node's pose.
  PoseEdge SequentialEdge(NodeId id, const Pose2& delta, bool odometry_lost,
                          const std::vector<Eigen::Vector2d>& points, Pose2* X_new,
                          StepStats* stats);
  /// Loop closing for the new node `current`: the local search, then the global one when
  /// the local one closed nothing; the closures they accept go into the graph.
  void CloseLoops(NodeId current, StepStats* stats);
  LoopClosingView View() const { return {graph, values, nodes, recent}; }
  /// Puts a verified closure into the graph (and optimizes when it is far off).
  void AddLoopEdge(const LoopHypothesis& h);
  /// Nodes that must neither be removed nor sparsified: those of pending hypotheses and of
  /// loop edges whose chi2 at the estimate exceeds loops.suspect_chi2.
  std::set<NodeId> UnsettledNodes() const;
  /// Optimizes and re-renders the scans that moved (SyncMap).
  void OptimizeAndSyncMap();
  /// Optimizes the graph only: the map keeps rendering the scans where it had them until the
  /// next SyncMap, as it does between optimizations.
  void Optimize();
  void SyncMap();
  void Prune(NodeId current);
  /// The gains the map tracks for a pruning round at X_cur, whose candidates are `nearby`
  /// (MapKeeper::TrackOnly).
  void TrackGainsAround(const Pose2& X_cur, const std::vector<NodeId>& nearby);
  void RemoveNode(NodeId id, double gain_bits);
  /// Traces beams of node id's scan cut in the map from now on (a policy found them
  /// outdated, SampleRetirement; a beam cut again is cut by the two cuts merged, Merge);
  /// the gains follow.
  void CutBeams(NodeId id, const std::vector<BeamCut>& cuts);
  std::size_t cut_beams = 0;  ///< cuts CutBeams applied, in all (a beam cut again counts again)
  /// Node id's scan as the overlap rule sees it (removal_policy.hpp), at its estimate.
  ScanFootprint Footprint(NodeId id) const;
  /// A pruning round's view of the mapper around `current` (all but its nearby nodes).
  void BindRoundView(NodeId current, RoundView* view) const;
};

}  // namespace lifelong::slam
