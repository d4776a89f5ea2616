// What pruning keeps between observations: the removal policy and the sparsifier (null in
// standard mode), what they did, and the index of the scans' information gains (a part of
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
  /// Every node's information gain, kept exact through every change of the map.
  GainIndex tracked;
  std::vector<CellState> counts_after;  ///< scratch: the cells as a change leaves them
  std::vector<CellChange> changes;      ///< scratch: the cells a move changed
  std::vector<CellUpdate> cells;        ///< scratch: a tracked scan's cells (GainIndex::Cells)

  bool active() const { return policy != nullptr; }
};

}  // namespace lifelong::slam
