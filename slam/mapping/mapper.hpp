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
#include "slam/loops/loop_verifier.hpp"
#include "slam/mapping/mapper_config.hpp"
#include "slam/mapping/mapper_records.hpp"
#include "types/stamped_pose.hpp"

namespace lifelong::slam {

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
  /// The map as the world most likely stands at the latest scan: f(cell, p(occ)) for every
  /// cell map() knows (ForEachPresentCell, grid.present_timescale_s).
  void ForEachPresentCell(const std::function<void(CellIndex, double)>& f) const;
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
  /// Cuts the removal policy applied in the map (mode pruned-dpg, BeamCut), in all; a beam
  /// cut again counts again.
  std::size_t cut_beams() const;
  /// Self-check of the pruned modes' tracked information gains (MapKeeper: the nodes of the
  /// last pruning round's neighbourhood and those added since): the largest difference (bits)
  /// between a tracked gain and the gain computed afresh from the map now. 0 when the
  /// bookkeeping is right (or nothing is tracked).
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
