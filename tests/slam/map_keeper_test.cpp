// MapKeeper tracks the gains of the scans near the robot only (TrackOnly): a scan outside is
// moved, cut and removed without its gain, the tracked gains stay exact through it, and its
// gain comes back equal to a fresh computation when it is tracked again.
#include "slam/mapping/map_keeper.hpp"

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "tests/slam/synthetic_scans.hpp"

namespace lifelong::slam {
namespace {

// The room scanned from six poses, every scan tracked (as after Add).
struct Room {
  testing::World world = testing::RoomWorld();
  NodeStore nodes;
  MapKeeper keeper;
  std::vector<CellIndex> seen;  ///< every cell a scan was ever rendered in

  void Saw(const NodeData& data) {
    for (const CellUpdate& u : keeper.grid().TouchedCells(data.scan, data.T_world_map, data.cuts))
      seen.push_back(u.cell);
  }

  explicit Room(const GridMapConfig& grid = {})
      : keeper(grid, true, GainTiming{[] { return nullptr; }, nullptr}) {
    const Pose2 poses[] = {{1.5, 2.0, 0.0}, {2.5, 3.3, 0.4}, {3.5, 2.0, -0.3},
                           {4.8, 3.0, 2.0}, {6.0, 2.2, 3.0}, {7.0, 1.0, 1.5}};
    NodeId id = 0;
    for (const Pose2& pose : poses) {
      NodeData& data = nodes[id];
      data.T_world_map = pose;
      data.scan = testing::SimulateScan(world, pose);
      data.scan.stamp_s = 10.0 * static_cast<double>(id);
      keeper.Add(id++, data.scan, pose);
      Saw(data);
    }
  }
  void Move(NodeId id, const Pose2& to) {
    NodeData& data = nodes.at(id);
    keeper.Move(id, data.scan, data.T_world_map, to, data.cuts);
    data.T_world_map = to;
    Saw(data);
  }
  // The largest difference between a tracked gain and its fresh computation (bits).
  double WorstGainError() const {
    double worst = 0.0;
    for (const auto& [id, data] : nodes) {
      if (!keeper.Tracks(id)) continue;
      const double fresh = keeper.FreshGain(data.scan, data.T_world_map, data.cuts);
      worst = std::max(worst, std::abs(fresh - keeper.Gain(id)));
    }
    return worst;
  }
  // Whether the keeper's grid holds exactly the nodes' scans as they are rendered now, in
  // every cell a scan was ever rendered in.
  bool GridHoldsTheNodes() {
    GridMap fresh;
    for (const auto& [id, data] : nodes) {
      fresh.Add(fresh.TouchedCells(data.scan, data.T_world_map, data.cuts));
      Saw(data);
    }
    for (const CellIndex c : seen) {
      const CellCounts a = fresh.Counts(c), b = keeper.grid().Counts(c);
      if (a.hits != b.hits || a.misses != b.misses || fresh.Lists(c) != keeper.grid().Lists(c))
        return false;
    }
    return true;
  }
};

TEST(MapKeeper, TracksOnlyTheNodesAskedFor) {
  Room room;
  for (NodeId id = 0; id < 6; ++id) EXPECT_TRUE(room.keeper.Tracks(id));
  room.keeper.TrackOnly({1, 2}, {}, room.nodes);
  for (NodeId id = 0; id < 6; ++id) EXPECT_EQ(room.keeper.Tracks(id), id == 1 || id == 2) << id;
  EXPECT_THROW(room.keeper.Gain(0), std::logic_error);
  EXPECT_LT(room.WorstGainError(), 1e-9);
  // Kept: tracked on if tracked, not started.
  room.keeper.TrackOnly({3}, {0, 1}, room.nodes);
  for (NodeId id = 0; id < 6; ++id) EXPECT_EQ(room.keeper.Tracks(id), id == 1 || id == 3) << id;
  EXPECT_LT(room.WorstGainError(), 1e-9);
}

// Untracked scans move and leave; the tracked gains follow, and an untracked scan's gain is
// exact again once tracked.
TEST(MapKeeper, TrackedGainsStayExactWhileUntrackedScansMoveAndLeave) {
  Room room;
  room.keeper.TrackOnly({1, 2, 3}, {}, room.nodes);
  room.Move(0, {1.6, 2.1, 0.05});  // untracked, overlaps the tracked ones
  room.Move(2, {3.45, 2.05, -0.28});
  room.Move(4, {5.9, 2.3, 3.05});
  EXPECT_LT(room.WorstGainError(), 1e-9);
  EXPECT_TRUE(room.GridHoldsTheNodes());
  const NodeData& gone = room.nodes.at(5);
  room.keeper.Remove(5, gone.scan, gone.T_world_map, gone.cuts);
  room.nodes.erase(5);
  EXPECT_TRUE(room.GridHoldsTheNodes());
  EXPECT_LT(room.WorstGainError(), 1e-9);
  room.keeper.TrackOnly({0, 4}, {}, room.nodes);
  EXPECT_TRUE(room.keeper.Tracks(0) && room.keeper.Tracks(4) && !room.keeper.Tracks(1));
  EXPECT_LT(room.WorstGainError(), 1e-9);
}

// A scan cut while untracked is retraced from the cells its old cuts left.
TEST(MapKeeper, AnUntrackedScanIsCutFromItsOldCuts) {
  Room room;
  NodeData& data = room.nodes.at(3);
  const std::vector<BeamCut> first{{10, 0.5f, 0.0f}, {40, 1.0f, 0.0f}};
  room.keeper.Retrace(3, data.scan, data.T_world_map, data.cuts, first);
  data.cuts = first;
  room.keeper.TrackOnly({0, 1}, {}, room.nodes);
  ASSERT_FALSE(room.keeper.Tracks(3));
  const std::vector<BeamCut> more = MergeCuts(first, {{90, 0.8f, 0.0f}});
  room.keeper.Retrace(3, data.scan, data.T_world_map, data.cuts, more);
  data.cuts = more;
  EXPECT_TRUE(room.keeper.Tracks(3));
  EXPECT_TRUE(room.GridHoldsTheNodes());
  EXPECT_LT(room.WorstGainError(), 1e-9);
}

// With the present view on, what a cut or a removal takes out of the grid goes to the ledger:
// the grid plus the ledger hold every scan as it was taken, and the ledger knows when each
// cell was last observed.
TEST(MapKeeper, TheLedgerHoldsWhatCutsAndRemovalsTookOut) {
  EXPECT_EQ(Room().keeper.ledger(), nullptr);  // off by default
  GridMapConfig grid;
  grid.present_timescale_s = 600.0;
  Room room(grid);
  GridMap taken;
  for (const auto& [id, data] : room.nodes)
    taken.Add(taken.TouchedCells(data.scan, data.T_world_map));
  NodeData& cut = room.nodes.at(3);
  const std::vector<BeamCut> cuts{{10, 0.5f, 0.0f}, {40, 1.0f, 1.4f}};
  room.keeper.Retrace(3, cut.scan, cut.T_world_map, cut.cuts, cuts);
  cut.cuts = cuts;
  const NodeData& gone = room.nodes.at(5);
  room.keeper.Remove(5, gone.scan, gone.T_world_map, gone.cuts);
  const CellLedger& ledger = *room.keeper.ledger();
  int changed = 0;
  taken.ForEachKnownCell([&](CellIndex c, CellCounts want) {
    const CellCounts shown = room.keeper.grid().Counts(c);
    const CellLedger::Entry* e = ledger.Find(c);
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(static_cast<std::int64_t>(shown.hits) + e->hits, want.hits);
    EXPECT_EQ(static_cast<std::int64_t>(shown.misses) + e->misses, want.misses);
    EXPECT_LE(ledger.SeenStamp(*e), 50.0);
    changed += e->changed ? 1 : 0;
  });
  EXPECT_GT(changed, 0);
  // The last scan's cells were last observed at its stamp.
  const CellUpdate last = room.keeper.grid().TouchedCells(gone.scan, gone.T_world_map).front();
  EXPECT_EQ(ledger.SeenStamp(*ledger.Find(last.cell)), 50.0);
  // A scan moved (a loop closure) is observed where it is rendered now, tracked or not.
  room.keeper.TrackOnly({1}, {}, room.nodes);
  for (const NodeId id : {NodeId{1}, NodeId{4}}) {
    room.Move(id, room.nodes.at(id).T_world_map * Pose2(0.3, 0.2, 0.1));
    const NodeData& moved = room.nodes.at(id);
    for (const CellUpdate& u : room.keeper.grid().TouchedCells(moved.scan, moved.T_world_map))
      EXPECT_GE(ledger.SeenStamp(*ledger.Find(u.cell)), moved.scan.stamp_s) << id;
  }
}

// A scan between keyframes is no node and stays out of the grid, but the cells its returns
// ended in were observed when it was taken.
TEST(MapKeeper, AGlimpseStampsTheCellsItsReturnsEndedIn) {
  GridMapConfig grid;
  grid.present_timescale_s = 600.0;
  Room room(grid);
  LaserScan glimpse = testing::SimulateScan(room.world, {3.0, 2.5, 1.0});
  glimpse.stamp_s = 99.0;
  const std::size_t known = room.keeper.grid().NumKnownCells();
  room.keeper.Glimpse(glimpse, {3.0, 2.5, 1.0});
  EXPECT_EQ(room.keeper.grid().NumKnownCells(), known);
  int hits = 0;
  for (const CellUpdate& u : room.keeper.grid().TouchedCells(glimpse, {3.0, 2.5, 1.0})) {
    if (u.delta.hits == 0) continue;
    ++hits;
    EXPECT_EQ(room.keeper.ledger()->SeenStamp(*room.keeper.ledger()->Find(u.cell)), 99.0);
  }
  EXPECT_GT(hits, 10);
}

}  // namespace
}  // namespace lifelong::slam
