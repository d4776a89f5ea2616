// The information gains of the pruned modes' scans (seed eq. 5.11). Every node's gain is
// tracked by a GainIndex, which keeps it exact through every change of the map: a scan added
// or moved gets its gain from the states its cells were left in, and each change updates the
// gains of the scans that share its cells.
#include "slam/mapping/mapper_state.hpp"

namespace lifelong::slam {

double Mapper::State::Gain(NodeId id) const {
  return static_cast<double>(prune_state.tracked.Gain(id)) * kEntropyQuantumBits;
}

const std::vector<CellUpdate>& Mapper::State::Untrack(NodeId id) {
  prune_state.tracked.Cells(id, &prune_state.cells);
  prune_state.tracked.Untrack(id);
  return prune_state.cells;
}

void Mapper::State::ChangeMap(const std::vector<CellUpdate>& cells, bool add) {
  std::vector<CellState>& after = prune_state.counts_after;
  add ? map.Add(cells, &after) : map.Remove(cells, &after);
  const ScopedMs timer = Stage(&StageTimes::gain_ms);
  prune_state.tracked.Apply(cells, after, add);
}

void Mapper::State::MoveInMap(const std::vector<CellUpdate>& from,
                              const std::vector<CellUpdate>& to) {
  map.Move(from, to, &prune_state.counts_after, &prune_state.changes);
  const ScopedMs timer = Stage(&StageTimes::gain_ms);
  prune_state.tracked.Apply(prune_state.changes);
}

void Mapper::State::TrackAdded(NodeId id, const std::vector<CellUpdate>& cells) {
  const ScopedMs timer = Stage(&StageTimes::gain_ms);
  prune_state.tracked.Track(id, cells, GainOfAdded(cells, prune_state.counts_after));
}

}  // namespace lifelong::slam
