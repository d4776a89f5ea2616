// What pruning keeps between observations: the removal policy and the sparsifier (null in
// standard mode), what they did, and the map changes since the last round (a part of
// Mapper::State; not public API).
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "slam/gain_index.hpp"
#include "slam/grid_map.hpp"
#include "slam/mapper.hpp"
#include "slam/removal_policy.hpp"
#include "slam/sparsifier.hpp"

namespace lifelong::slam {

/// Where an increment list lies: its cell box and a bitmap of the 16 x 16-cell blocks it
/// touches. Two lists can share a cell only if their footprints share a block, a much finer
/// test than the boxes (a scan's box spans walls and rooms it never sees into).
struct Footprint {
  static constexpr int kBlockBits = 4;  ///< blocks of 2^4 x 2^4 cells
  CellBounds box;
  CellIndex first_block;            ///< block of box.min
  int blocks_x = 0, blocks_y = 0;   ///< blocks spanned by the box
  std::vector<std::uint64_t> bits;  ///< row-major over the box's blocks

  static Footprint Of(const std::vector<CellUpdate>& cells);
  bool Shares(const Footprint& other) const;
  bool HasBlock(int bx, int by) const;
};

/// An edge whose information was scaled for a marginalization, and what it was before.
struct WeighedEdge {
  std::size_t index;  ///< into PoseGraph::edges()
  Eigen::Matrix3d information;
};

/// Scales the information of the robust (loop) edges with both ends in `set` (ascending) by
/// the kernel's IRLS weight rho'(e^T Omega e) at `values`, so a marginalization sees them as
/// the optimizer does (pruning.robust_marginal). Returns what it changed.
std::vector<WeighedEdge> WeighRobustEdges(PoseGraph* graph, const Values& values,
                                          const std::vector<NodeId>& set,
                                          const OptimizerParams& params);

struct PruningState {
  std::unique_ptr<RemovalPolicy> policy;   ///< which node goes
  std::unique_ptr<Sparsifier> sparsifier;  ///< what replaces its clique
  std::vector<MarginalizationRecord> marginalizations;
  std::vector<SparsificationRecord> sparsifications;
  /// A change of the map's counts, numbered in the order they happen.
  struct MapChange {
    std::uint64_t number;
    Footprint cells;
  };
  std::vector<MapChange> map_changes;  ///< since the last pruning round
  std::uint64_t changes_made = 0;      ///< number of the latest change
  /// The gains of the scans near the robot (those with cell lists), kept exact through every
  /// change; the other nodes remember theirs until a change shares a block with them.
  GainIndex tracked;
  std::vector<CellState> counts_after;  ///< scratch: the cells as a change leaves them

  bool active() const { return policy != nullptr; }
  /// Records that the map's counts changed in these cells (pruned modes).
  void NoteMapChange(const Footprint& cells) {
    if (active()) map_changes.push_back({++changes_made, cells});
  }
  /// Whether a map change since the last pruning round, made after change `seen` (the latest
  /// one a gain was computed after), touches a scan with this footprint. A gain computed in
  /// the last round after a removal has seen that removal.
  bool ChangedSince(const Footprint& scan, std::uint64_t seen) const {
    return std::any_of(map_changes.begin(), map_changes.end(), [&](const MapChange& change) {
      return change.number > seen && scan.Shares(change.cells);
    });
  }
};

}  // namespace lifelong::slam
