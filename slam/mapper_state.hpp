// Internal state of the Mapper, shared by mapper.cpp, loop_closing.cpp and pruning.cpp.
// Not part of the public API.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <vector>

#include <Eigen/Core>

#include "slam/dijkstra.hpp"
#include "slam/grid_map.hpp"
#include "slam/loop_closing_state.hpp"
#include "slam/loop_verifier.hpp"
#include "slam/mapper.hpp"
#include "slam/place_index.hpp"
#include "slam/pose_graph.hpp"
#include "slam/pruning_state.hpp"
#include "slam/removal_policy.hpp"
#include "slam/scan_matcher.hpp"
#include "slam/sparsifier.hpp"
#include "slam/surface_cache.hpp"

namespace lifelong::slam {

struct NodeData {
  LaserScan scan;
  std::vector<Eigen::Vector2d> points;  ///< thinned return end points, robot frame
  Pose2 T_world_map;                    ///< pose at which the scan is rendered in the map
  Pose2 T_odom_robot;                   ///< odometry at the scan
  int scan_index = 0;
  double travelled_m = 0.0;  ///< robot path length (odometry) at this scan
};

/// Adds the wall time of its scope, in ms, to *total, less the time of the timers nested in
/// it, so that the per-stage times of StepStats never count a moment twice (the map update
/// inside the matching stage, say, is the gains' when it updates gains). Nothing when total
/// is null. `innermost` is the timers' stack top, kept by the caller.
class ScopedMs {
 public:
  ScopedMs(double* total, ScopedMs** innermost)
      : total_(total),
        innermost_(innermost),
        parent_(total ? *innermost : nullptr),
        start_(std::chrono::steady_clock::now()) {
    if (total_) *innermost_ = this;
  }
  ~ScopedMs() {
    if (!total_) return;
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
            .count();
    *total_ += ms - nested_ms_;
    if (parent_) parent_->nested_ms_ += ms;
    *innermost_ = parent_;
  }
  ScopedMs(const ScopedMs&) = delete;
  ScopedMs& operator=(const ScopedMs&) = delete;

 private:
  double* total_;
  ScopedMs** innermost_;
  ScopedMs* parent_;
  std::chrono::steady_clock::time_point start_;
  double nested_ms_ = 0.0;
};

/// Where a scan of the stream is held: relative to an anchor node.
struct ScanAnchor {
  double stamp_s = 0.0;
  NodeId anchor = 0;
  Pose2 T_anchor_scan;
  Pose2 T_odom_robot;
};

struct Mapper::State {
  /// std::invalid_argument when the config names an unknown policy or sparsifier.
  explicit State(const MapperConfig& c);

  MapperConfig config;
  LoopClosingState loop_state;
  PruningState prune_state;
  PoseGraph graph;
  Values values;
  GridMap map;
  std::map<NodeId, NodeData> nodes;
  std::vector<NodeId> recent;  ///< node ids in insertion order (surviving ones)
  std::vector<ScanAnchor> scans;
  std::map<NodeId, std::vector<std::size_t>> scans_of_node;
  std::vector<std::size_t> pending;  ///< non-keyframe scans since the last node
  NodeId next_id = 0;
  int observations = 0;
  StepStats* step = nullptr;            ///< stats of the observation being processed
  ScopedMs* innermost_timer = nullptr;  ///< of the stage timers running
  bool have_last = false;
  NodeId last_node = 0;
  ReferenceGrid match_grid;  ///< the matchers' table, rebuilt in place for each match
  /// The surface points (robot frame) of the nodes in the last local map, kept while they
  /// stay in it (SurfaceRule::JoinsAny).
  std::map<NodeId, std::vector<Eigen::Vector2d>> local_surfaces;
  /// The loop closer's surface points (robot frame) of the nodes its recent submaps used
  /// (64 nodes: 80 % of the lookups on Intel hit, against 83 % with 256 and 57 % with 32).
  SurfaceCache loop_surfaces{64};
  /// The nodes' place descriptors (loops.global), searchable by ring key.
  PlaceIndex places;

  /// Times its scope as the stage `field` of the observation being processed (none when
  /// there is none).
  ScopedMs Stage(double StageTimes::*field) {
    return ScopedMs(step ? &(step->stages.*field) : nullptr, &innermost_timer);
  }

  void AddSequentialNode(const Observation& obs, StepStats* stats);
  void AnchorScan(const Observation& obs);
  /// The incremental matcher's reference in the world frame: the last local_map_nodes
  /// nodes' return points, or their surfaces (SurfaceRule::JoinsAny).
  std::vector<Eigen::Vector2d> LocalMap();
  /// Node id's points for a loop-closing reference, in the world frame: its surfaces when
  /// loops.surfaces is set (and the incremental rule makes any), its return points otherwise.
  std::vector<Eigen::Vector2d> LoopReference(NodeId id);
  /// Node id's surfaces in the robot frame, by `rule` (SurfacePoints), sampled
  /// at the thinning spacing (the likelihood field's resolution without thinning).
  std::vector<Eigen::Vector2d> SurfacesOf(NodeId id, const SurfaceRule& rule) const;
  void Reanchor(std::size_t scan, NodeId anchor);
  /// The Dijkstra projection of the covariances from `current` (loops.max_position_sigma_m),
  /// which both loop searches of an observation use.
  std::map<NodeId, ProjectedNode> ProjectFrom(NodeId current) const;
  /// The local search: the candidates inside the projected uncertainty, matched as a submap.
  bool TryCloseLoop(NodeId current, const std::map<NodeId, ProjectedNode>& projected);
  /// The global search (loops.global): the places most like the current node's, wherever
  /// the estimate puts them, matched in a wide window; then verified as any closure.
  bool TryGlobalLoop(NodeId current, const PlaceDescriptor& place,
                     const std::map<NodeId, ProjectedNode>& projected);
  /// Matches the current node's points against the submap's loop references around `guess`:
  /// the match when it has enough points in reach, scores, is unambiguous and locally
  /// unique; else nothing and *why.
  std::optional<MatchResult> MatchSubmap(const std::set<NodeId>& submap, NodeId current,
                                         const Pose2& guess, const MatcherConfig& mc,
                                         MatchRefusal* why);
  /// The match's correction of the current pose lies inside the consistency gate
  /// (loops.consistency_chi2) of `covariance` plus the match's own.
  bool Plausible(const MatchResult& match, NodeId current, const Eigen::Matrix3d& covariance) const;
  /// The closure old -> current measured by `match` (refined against old alone), proposed to
  /// the verifier; true when that put closures into the graph.
  bool ProposeClosure(NodeId old, NodeId current, const MatchResult& match);
  /// The place descriptor of `id` from its points and its recent neighbours', in its frame.
  PlaceDescriptor DescribeNode(NodeId id) const;
  /// Local uniqueness of a loop-closure match: no pose uniqueness_radius_m away (8
  /// directions, same heading) scores above max_flatness times the best.
  bool LocallyUnique(const MatchResult& match, const std::vector<Eigen::Vector2d>& points) const;
  /// The submap match measured again against node `old`'s scan alone (loops.refine_window_m);
  /// the submap match itself when that fails.
  MatchResult RefineAgainstNode(NodeId old, const std::vector<Eigen::Vector2d>& points,
                                const MatchResult& submap_match);
  /// The false-closure test: moves every 1/share-th hypothesis by the configured offset.
  void MaybeInjectFalse(LoopHypothesis* h);
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
  /// Information gain of node `id`'s scan (pruned modes), exact for the map as it is.
  double Gain(NodeId id) const;
  /// Stops tracking node `id`'s gain (before its cells move or leave the map) and gives its
  /// cells at its map pose, from the index (valid until the next call).
  const std::vector<CellUpdate>& Untrack(NodeId id);
  /// Adds an increment list to the map (or removes it) in a pruned mode; the gains follow.
  void ChangeMap(const std::vector<CellUpdate>& cells, bool add);
  /// Replaces an increment list in the map by another (GridMap::Move: a moved scan's cells
  /// at its old and new pose); the gains of the other scans follow. The moved scan must not
  /// be tracked; TrackAdded tracks it again.
  void MoveInMap(const std::vector<CellUpdate>& from, const std::vector<CellUpdate>& to);
  /// Starts tracking the gain of node `id`, whose cells ChangeMap or MoveInMap has just
  /// added: the gain comes from the states they were left in.
  void TrackAdded(NodeId id, const std::vector<CellUpdate>& cells);
  void Prune(NodeId current);
  void RemoveNode(NodeId id, double gain_bits);
  /// While the graph holds more than max_edges_per_node edges per node, replaces the edges
  /// in the Markov blanket (node + neighbours) with the most edges beyond a tree by their
  /// Chow-Liu tree, or, when every blanket is a tree, those of the two-hop neighbourhood with
  /// the most; at most a few per call. (The pruned graph is small: every node is considered.)
  void KeepEdgeBudget();
};

/// Points of the robot frame in the world frame of pose T.
std::vector<Eigen::Vector2d> ToWorld(const std::vector<Eigen::Vector2d>& points, const Pose2& T);

/// Rotates a world-frame (x, y, theta) covariance or information into the frame of a pose
/// with heading theta_rad: R^T M R on the translation block.
Eigen::Matrix3d RotateIntoFrame(const Eigen::Matrix3d& m, double theta_rad);

}  // namespace lifelong::slam
