// What the pruned modes keep of the map between observations: the index of the scans'
// information gains and its scratch (a part of Mapper::State; not public API).
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "slam/grid/gain_index.hpp"
#include "slam/grid/grid_map.hpp"
#include "slam/mapping/mapper.hpp"

namespace lifelong::slam {

struct PruningState {
  /// Every node's information gain, kept exact through every change of the map.
  GainIndex tracked;
  std::vector<CellState> counts_after;  ///< scratch: the cells as a change leaves them
  std::vector<CellChange> changes;      ///< scratch: the cells a move changed
  std::vector<CellUpdate> cells;        ///< scratch: a tracked scan's cells (GainIndex::Cells)
};

}  // namespace lifelong::slam
