// The mapper's map: the counting grid (seed §5.1) and, in the pruned modes, the information
// gains (seed eq. 5.11) of the scans near the robot, kept exact through every change of the
// grid by a GainIndex. A scan enters, moves, has beams cut and leaves through the keeper;
// nothing else writes the grid. In the standard mode no gain is kept and a scan is rendered
// and moved as it is.
//
// Only the scans of the pruning neighbourhood are tracked (TrackOnly): a scan far from the
// robot is moved as in the standard mode, traced at both poses, and its gain computed afresh
// from the grid when the robot comes back. A gain kept by the index equals the gain computed
// afresh bit for bit, so which scans are tracked changes no result, only the cost: tracking
// every scan re-encoded each one the optimizer moved (the campus log's loop closures move
// hundreds), some 9 s of its 113 s pruned replay (docs/results.md).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "sensor/laser_scan.hpp"
#include "sensor/pose2.hpp"
#include "slam/graph/pose_graph.hpp"
#include "slam/grid/cell_ledger.hpp"
#include "slam/grid/gain_index.hpp"
#include "slam/grid/grid_map.hpp"
#include "slam/mapping/scoped_ms.hpp"
#include "slam/matching/node_data.hpp"

namespace lifelong::slam {

/// Where the gain bookkeeping is timed: the current observation's gain stage (null: not
/// timed) and the stage timers' stack top (ScopedMs).
struct GainTiming {
  std::function<double*()> sink;
  ScopedMs** innermost = nullptr;
};

class MapKeeper {
 public:
  /// track_gains: the pruned modes' gain index. With it and grid.present_timescale_s > 0, a
  /// CellLedger too: what removals and cuts take out of the grid, and when each cell was last
  /// observed (the map as it stands now, present_view.hpp).
  MapKeeper(const GridMapConfig& grid, bool track_gains, GainTiming timing);

  /// Renders node id's scan at T (and, with gains, tracks its gain: a new scan is near the
  /// robot).
  void Add(NodeId id, const LaserScan& scan, const Pose2& T);
  /// Node id's scan, rendered at `from`, rendered at `to` instead; with gains its beams
  /// `cuts` stay cut (the standard mode cuts none).
  void Move(NodeId id, const LaserScan& scan, const Pose2& from, const Pose2& to,
            const std::vector<BeamCut>& cuts);
  /// With gains: node id's scan, rendered at T with the beams `old_cuts` cut, traced again
  /// with `cuts` cut (a policy found them outdated); the gains of the scans sharing its cells
  /// follow, and its own gain is tracked.
  void Retrace(NodeId id, const LaserScan& scan, const Pose2& T,
               const std::vector<BeamCut>& old_cuts, const std::vector<BeamCut>& cuts);
  /// A scan that is not a node, taken at T: with a ledger, the cells its returns ended in
  /// were observed at its stamp (a glimpse between keyframes; the grid does not take it).
  void Glimpse(const LaserScan& scan, const Pose2& T);
  /// With gains: tracks the gains of the nodes `wanted` (of `nodes`, each rendered at its
  /// T_world_map), keeps tracking those of `kept` that are, and stops tracking every other.
  /// The pruning round asks for the gains of the nodes within its radius only.
  void TrackOnly(const std::vector<NodeId>& wanted, const std::vector<NodeId>& kept,
                 const NodeStore& nodes);
  /// Whether node id's gain is tracked (Gain answers for it).
  bool Tracks(NodeId id) const { return gains_.Tracks(id); }
  /// The map follows the estimate: every node whose pose in `values` moved more than
  /// epsilon_m or turned more than epsilon_rad from where its scan is rendered
  /// (NodeData::T_world_map) is rendered there instead, and its T_world_map updated.
  void Follow(const Values& values, double epsilon_m, double epsilon_rad, NodeStore* nodes);
  /// With gains: node id's scan, rendered at T with the beams `cuts` cut, leaves the grid.
  void Remove(NodeId id, const LaserScan& scan, const Pose2& T, const std::vector<BeamCut>& cuts);

  /// Information gain of node id's scan, bits, exact for the grid as it is (pruned modes;
  /// std::logic_error when it is not tracked).
  double Gain(NodeId id) const;
  /// The gain of node id's scan at T computed afresh from the grid, bits (a check of Gain).
  double FreshGain(const LaserScan& scan, const Pose2& T, const std::vector<BeamCut>& cuts) const;
  const GridMap& grid() const { return grid_; }
  /// Null unless kept (the constructor).
  const CellLedger* ledger() const { return ledger_.get(); }

 private:
  const std::vector<CellUpdate>& Untrack(NodeId id);
  /// A tracked scan rendered at T with `cuts` instead of where the index holds it.
  /// recut: at the same pose, with other cuts (the ledger archives what they take out).
  void Rerender(NodeId id, const LaserScan& scan, const Pose2& T, const std::vector<BeamCut>& cuts,
                bool recut = false);
  /// Starts tracking node id's scan as rendered at T with `cuts` (a no-op when tracked).
  void Watch(NodeId id, const LaserScan& scan, const Pose2& T, const std::vector<BeamCut>& cuts);
  void Change(const std::vector<CellUpdate>& cells, bool add);
  void MoveCells(const std::vector<CellUpdate>& from, const std::vector<CellUpdate>& to);
  void Track(NodeId id, const std::vector<CellUpdate>& cells);
  ScopedMs GainTimer() const { return ScopedMs(timing_.sink(), timing_.innermost); }

  GridMap grid_;
  bool track_gains_;
  GainTiming timing_;
  GainIndex gains_;                      ///< every node's information gain
  std::unique_ptr<CellLedger> ledger_;   ///< what left the grid, and when cells were seen
  std::vector<CellState> counts_after_;  ///< scratch: the cells as a change leaves them
  std::vector<CellChange> changes_;      ///< scratch: the cells a move changed
  std::vector<CellUpdate> cells_;        ///< scratch: a tracked scan's cells (GainIndex::Cells)
};

}  // namespace lifelong::slam
