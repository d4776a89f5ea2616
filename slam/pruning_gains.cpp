// The information gains of the pruned modes' scans (seed eq. 5.11). The scans near the
// robot are tracked by a GainIndex, which keeps their gains exact through every change of
// the map; every other node remembers its gain until a change shares a block with its scan.
#include <map>

#include "slam/mapper_state.hpp"

namespace lifelong::slam {

const std::vector<CellUpdate>& Mapper::State::Touched(NodeId id) {
  NodeData& data = nodes.at(id);
  if (data.touched.empty()) data.touched = map.TouchedCells(data.scan, data.T_world_map);
  // (The footprint is kept when the list is freed: it is set wherever the list is computed
  // at a new pose.)
  return data.touched;
}

double Mapper::State::Gain(NodeId id) {
  GainIndex& tracked = prune_state.tracked;
  NodeData& data = nodes.at(id);
  if (tracked.Tracks(id)) return static_cast<double>(tracked.Gain(id)) * kEntropyQuantumBits;
  if (!data.gain_valid) {
    const ScopedMs timer = Stage(&StageTimes::gain_ms);
    data.gain_quanta = map.QuantizedGain(Touched(id));
    data.gain_valid = true;
  }
  // A remembered gain is exact too (else it would have been forgotten): from now on the
  // index keeps it so, if the cell list is at hand.
  if (!data.touched.empty()) {
    const ScopedMs timer = Stage(&StageTimes::gain_ms);
    tracked.Track(id, data.touched, data.gain_quanta);
  }
  data.gain_seen = prune_state.changes_made;
  return data.GainBits();
}

void Mapper::State::Untrack(NodeId id) {
  GainIndex& tracked = prune_state.tracked;
  if (!tracked.Tracks(id)) return;
  const ScopedMs timer = Stage(&StageTimes::gain_ms);
  NodeData& data = nodes.at(id);
  data.gain_quanta = tracked.Untrack(id);
  data.gain_valid = true;
  data.gain_seen = prune_state.changes_made;
}

void Mapper::State::ChangeMap(const std::vector<CellUpdate>& cells, const Footprint& footprint,
                              bool add) {
  if (!prune_state.active()) {
    add ? map.Add(cells) : map.Remove(cells);
    return;
  }
  std::vector<CellState>& after = prune_state.counts_after;
  add ? map.Add(cells, &after) : map.Remove(cells, &after);
  GainIndex& tracked = prune_state.tracked;
  if (tracked.Reaches(footprint.box)) {
    const ScopedMs timer = Stage(&StageTimes::gain_ms);
    tracked.Apply(cells, after, add);
  }
  prune_state.NoteMapChange(footprint);
}

void Mapper::State::TrackAdded(NodeId id) {
  const ScopedMs timer = Stage(&StageTimes::gain_ms);
  NodeData& data = nodes.at(id);
  data.gain_quanta = GainOfAdded(data.touched, prune_state.counts_after);
  data.gain_valid = true;
  data.gain_seen = prune_state.changes_made;
  prune_state.tracked.Track(id, data.touched, data.gain_quanta);
}

void Mapper::State::ForgetStaleGains() {
  for (auto& [id, data] : nodes) {
    if (data.gain_valid && !prune_state.tracked.Tracks(id) &&
        prune_state.ChangedSince(data.footprint, data.gain_seen)) {
      data.gain_valid = false;
    }
  }
}

std::int64_t Mapper::State::KnownGain(NodeId id) const {
  const NodeData& data = nodes.at(id);
  return prune_state.tracked.Tracks(id) ? prune_state.tracked.Gain(id) : data.gain_quanta;
}

}  // namespace lifelong::slam
