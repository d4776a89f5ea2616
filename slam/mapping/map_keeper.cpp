#include "slam/mapping/map_keeper.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace lifelong::slam {

MapKeeper::MapKeeper(const GridMapConfig& grid, bool track_gains, GainTiming timing)
    : grid_(grid), track_gains_(track_gains), timing_(std::move(timing)) {
  if (track_gains_ && grid.present_timescale_s > 0.0) ledger_ = std::make_unique<CellLedger>();
}

void MapKeeper::Add(NodeId id, const LaserScan& scan, const Pose2& T) {
  if (!track_gains_) {
    grid_.AddScan(scan, T);
    return;
  }
  const std::vector<CellUpdate> added = grid_.TouchedCells(scan, T);
  if (ledger_) ledger_->Observe(added, scan.stamp_s);
  Change(added, true);
  Track(id, added);
}

void MapKeeper::Glimpse(const LaserScan& scan, const Pose2& T) {
  if (ledger_) ledger_->Observe(grid_.ReturnCells(scan, T), scan.stamp_s);
}

void MapKeeper::Move(NodeId id, const LaserScan& scan, const Pose2& from, const Pose2& to,
                     const std::vector<BeamCut>& cuts) {
  if (!track_gains_) {
    grid_.MoveScan(scan, from, to);
    return;
  }
  if (gains_.Tracks(id)) {
    Rerender(id, scan, to, cuts);
    return;
  }
  // Far from the robot: moved as the standard mode moves it, the tracked gains updated.
  Change(grid_.TouchedCells(scan, from, cuts), false);
  const std::vector<CellUpdate> moved = grid_.TouchedCells(scan, to, cuts);
  if (ledger_) ledger_->Observe(moved, scan.stamp_s);
  Change(moved, true);
}

void MapKeeper::Retrace(NodeId id, const LaserScan& scan, const Pose2& T,
                        const std::vector<BeamCut>& old_cuts, const std::vector<BeamCut>& cuts) {
  Watch(id, scan, T, old_cuts);
  Rerender(id, scan, T, cuts, true);
}

void MapKeeper::Rerender(NodeId id, const LaserScan& scan, const Pose2& T,
                         const std::vector<BeamCut>& cuts, bool recut) {
  // The cells where it is rendered now come from the gain index, which holds them anyway.
  const std::vector<CellUpdate>& from = Untrack(id);
  const std::vector<CellUpdate> to = grid_.TouchedCells(scan, T, cuts);
  if (ledger_) {
    if (recut) ledger_->Recut(from, to);
    ledger_->Observe(to, scan.stamp_s);
  }
  MoveCells(from, to);
  Track(id, to);
}

void MapKeeper::TrackOnly(const std::vector<NodeId>& wanted, const std::vector<NodeId>& kept,
                          const NodeStore& nodes) {
  if (!track_gains_) return;
  const ScopedMs timer = GainTimer();
  std::vector<NodeId> keep = kept;
  keep.insert(keep.end(), wanted.begin(), wanted.end());
  std::sort(keep.begin(), keep.end());
  for (const NodeId id : gains_.Ids()) {
    if (!std::binary_search(keep.begin(), keep.end(), id)) gains_.Untrack(id);
  }
  for (const NodeId id : wanted) {
    const NodeData& data = nodes.at(id);
    Watch(id, data.scan, data.T_world_map, data.cuts);
  }
}

void MapKeeper::Watch(NodeId id, const LaserScan& scan, const Pose2& T,
                      const std::vector<BeamCut>& cuts) {
  if (gains_.Tracks(id)) return;
  const std::vector<CellUpdate> cells = grid_.TouchedCells(scan, T, cuts);
  gains_.Track(id, cells, grid_.QuantizedGain(cells));
}

void MapKeeper::Follow(const Values& values, double epsilon_m, double epsilon_rad,
                       NodeStore* nodes) {
  for (auto& [id, data] : *nodes) {
    const Pose2& X = values.at(id);
    const Pose2 d = Between(data.T_world_map, X);
    if (Norm(d) > epsilon_m || std::abs(d.theta) > epsilon_rad) {
      Move(id, data.scan, data.T_world_map, X, data.cuts);
      data.T_world_map = X;
    }
  }
}

void MapKeeper::Remove(NodeId id, const LaserScan& scan, const Pose2& T,
                       const std::vector<BeamCut>& cuts) {
  const auto leave = [this](const std::vector<CellUpdate>& cells) {
    if (ledger_) ledger_->Archive(cells);
    Change(cells, false);
  };
  if (gains_.Tracks(id)) {
    leave(Untrack(id));
  } else {
    leave(grid_.TouchedCells(scan, T, cuts));
  }
}

double MapKeeper::Gain(NodeId id) const {
  return static_cast<double>(gains_.Gain(id)) * kEntropyQuantumBits;
}

double MapKeeper::FreshGain(const LaserScan& scan, const Pose2& T,
                            const std::vector<BeamCut>& cuts) const {
  return grid_.InformationGain(grid_.TouchedCells(scan, T, cuts));
}

const std::vector<CellUpdate>& MapKeeper::Untrack(NodeId id) {
  gains_.Cells(id, &cells_);
  gains_.Untrack(id);
  return cells_;
}

void MapKeeper::Change(const std::vector<CellUpdate>& update, bool add) {
  add ? grid_.Add(update, &counts_after_) : grid_.Remove(update, &counts_after_);
  const ScopedMs timer = GainTimer();
  gains_.Apply(update, counts_after_, add);
}

void MapKeeper::MoveCells(const std::vector<CellUpdate>& from, const std::vector<CellUpdate>& to) {
  grid_.Move(from, to, &counts_after_, &changes_);
  const ScopedMs timer = GainTimer();
  gains_.Apply(changes_);
}

void MapKeeper::Track(NodeId id, const std::vector<CellUpdate>& added) {
  const ScopedMs timer = GainTimer();
  gains_.Track(id, added, GainOfAdded(added, counts_after_));
}

}  // namespace lifelong::slam
