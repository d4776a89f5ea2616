// GainIndex keeps the information gains (seed eq. 5.11) of tracked scans exact through every
// change of the map, bit for bit equal to the gains computed afresh, including where it skips
// the cells of pure counts.
#include "slam/grid/gain_index.hpp"

#include <algorithm>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/slam/synthetic_scans.hpp"

namespace lifelong::slam {
namespace {

// Scans of the room from random poses, with the room straddling cell 0 (negative indices,
// chunk boundaries).
std::vector<std::vector<CellUpdate>> RandomLists(const GridMap& map, int n, unsigned seed) {
  const testing::World room = testing::RoomWorld();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(0.5, 7.5), y(0.5, 4.5), theta(-3.1, 3.1);
  const Pose2 shift(-4.0, -2.5, 0.0);
  std::vector<std::vector<CellUpdate>> lists;
  for (int i = 0; i < n; ++i) {
    const Pose2 pose(x(rng), y(rng), theta(rng));
    lists.push_back(map.TouchedCells(testing::SimulateScan(room, pose), shift * pose));
  }
  return lists;
}

// The map and index together, as the mapper keeps them.
struct Fixture {
  GridMap map;
  GainIndex index;
  std::vector<CellState> after;

  void Change(const std::vector<CellUpdate>& cells, bool add) {
    add ? map.Add(cells, &after) : map.Remove(cells, &after);
    index.Apply(cells, after, add);
  }
};

TEST(GainIndex, TrackedGainsEqualFreshOnesThroughAddsRemovesAndMoves) {
  Fixture f;
  const auto lists = RandomLists(f.map, 24, 7);
  std::map<NodeId, bool> in_map;
  // Half the scans go in untracked, then every other one is tracked.
  for (NodeId i = 0; i < 12; ++i) {
    f.Change(lists[i], true);
    in_map[i] = true;
    if (i % 2 == 0) f.index.Track(i, lists[i], f.map.QuantizedGain(lists[i]));
  }
  std::mt19937 rng(11);
  int checked = 0;
  for (int step = 0; step < 60; ++step) {
    const NodeId id = static_cast<NodeId>(rng() % lists.size());
    if (f.index.Tracks(id)) {
      f.index.Untrack(id);  // before its cells leave the map
    }
    f.Change(lists[id], !in_map[id]);
    in_map[id] = !in_map[id];
    if (in_map[id] && step % 3 == 0) f.index.Track(id, lists[id], f.map.QuantizedGain(lists[id]));
    for (const auto& [n, present] : in_map) {
      if (!present || !f.index.Tracks(n)) continue;
      ASSERT_EQ(f.index.Gain(n), f.map.QuantizedGain(lists[n])) << "node " << n << " step " << step;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

// Moves (GridMap::Move, its change list applied once) keep the tracked gains exact too:
// scans nudged by a few centimetres (most cells unchanged), now and then one moved far.
TEST(GainIndex, TrackedGainsEqualFreshOnesThroughMoves) {
  Fixture f;
  const testing::World room = testing::RoomWorld();
  const Pose2 shift(-4.0, -2.5, 0.0);
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> x(0.5, 7.5), y(0.5, 4.5), theta(-3.1, 3.1),
      nudge(-0.03, 0.03);
  std::vector<LaserScan> scans;
  std::vector<Pose2> poses;
  std::vector<std::vector<CellUpdate>> at;
  for (NodeId i = 0; i < 10; ++i) {
    poses.emplace_back(x(rng), y(rng), theta(rng));
    scans.push_back(testing::SimulateScan(room, poses.back()));
    at.push_back(f.map.TouchedCells(scans.back(), shift * poses.back()));
    f.Change(at.back(), true);
  }
  for (NodeId i = 0; i < 10; ++i) f.index.Track(i, at[i], f.map.QuantizedGain(at[i]));
  std::vector<CellChange> changes;
  for (int step = 0; step < 40; ++step) {
    const auto id = static_cast<NodeId>(rng() % at.size());
    const Pose2& p = poses[id];
    poses[id] = step % 8 == 7
                    ? Pose2(x(rng), y(rng), theta(rng))
                    : Pose2(p.x + nudge(rng), p.y + nudge(rng), p.theta + 0.2 * nudge(rng));
    std::vector<CellUpdate> to = f.map.TouchedCells(scans[id], shift * poses[id]);
    f.index.Untrack(id);
    f.map.Move(at[id], to, &f.after, &changes);
    f.index.Apply(changes);
    f.index.Track(id, to, GainOfAdded(to, f.after));
    at[id] = std::move(to);
    for (NodeId n = 0; n < 10; ++n) {
      ASSERT_EQ(f.index.Gain(n), f.map.QuantizedGain(at[n])) << "node " << n << " step " << step;
    }
  }
}

// The index gives back each tracked scan's list as it got it: the same cells, increments and
// order, across chunk boundaries and negative indices (the room straddles cell 0).
TEST(GainIndex, GivesBackTheListsItTracks) {
  Fixture f;
  const auto lists = RandomLists(f.map, 6, 21);
  for (NodeId i = 0; i < 6; ++i) f.index.Track(i, lists[i], 0);
  f.index.Untrack(2);
  std::vector<CellUpdate> cells{{{1, 1}, {1, 1}}};  // replaced, not appended to
  for (NodeId i = 0; i < 6; ++i) {
    if (i == 2) {
      EXPECT_THROW(f.index.Cells(i, &cells), std::logic_error);
      continue;
    }
    f.index.Cells(i, &cells);
    ASSERT_EQ(cells.size(), lists[i].size());
    for (std::size_t k = 0; k < cells.size(); ++k) {
      EXPECT_EQ(cells[k].cell, lists[i][k].cell) << "node " << i << " cell " << k;
      EXPECT_EQ(cells[k].delta.hits, lists[i][k].delta.hits);
      EXPECT_EQ(cells[k].delta.misses, lists[i][k].delta.misses);
    }
  }
}

// A list with a count beyond 16 bits (a dense sensor) is held wide: its gain and its cells
// stay exact beside narrow ones.
TEST(GainIndex, ListsWithCountsBeyondSixteenBitsAreHeldWide) {
  Fixture f;
  const std::vector<CellUpdate> wide{
      {{-1, 0}, {0, 70000}}, {{0, 0}, {3, 65536}}, {{40, 0}, {1, 0}}};
  const std::vector<CellUpdate> narrow{{{-1, 0}, {0, 1}}, {{0, 0}, {65535, 2}}, {{40, 0}, {0, 5}}};
  f.Change(wide, true);
  f.index.Track(0, wide, f.map.QuantizedGain(wide));
  f.Change(narrow, true);
  f.index.Track(1, narrow, GainOfAdded(narrow, f.after));
  EXPECT_EQ(f.index.Gain(0), f.map.QuantizedGain(wide));
  EXPECT_EQ(f.index.Gain(1), f.map.QuantizedGain(narrow));
  std::vector<CellUpdate> cells;
  for (const auto& [id, list] : {std::pair{0, wide}, std::pair{1, narrow}}) {
    f.index.Cells(id, &cells);
    ASSERT_EQ(cells.size(), list.size());
    for (std::size_t k = 0; k < cells.size(); ++k) {
      EXPECT_EQ(cells[k].cell, list[k].cell);
      EXPECT_EQ(cells[k].delta.hits, list[k].delta.hits);
      EXPECT_EQ(cells[k].delta.misses, list[k].delta.misses);
    }
  }
  f.index.Untrack(1);
  f.Change(narrow, false);
  EXPECT_EQ(f.index.Gain(0), f.map.QuantizedGain(wide));
}

// Each piece is held in the narrowest width its counts fit: 4 bits a count up to 15, 16 bits
// up to 65 535, 32 beyond. At the boundaries the gains stay exact through changes of the map
// (a piece of each width beside the others), and the cells come back as tracked.
TEST(GainIndex, EachPieceIsHeldInTheNarrowestWidthItsCountsFit) {
  Fixture f;
  // One piece per 32-cell chunk: counts of 15 (4 bits), 16 (16 bits) and 65 536 (32 bits).
  const std::vector<CellUpdate> mixed{{{0, 0}, {15, 15}},    {{1, 0}, {0, 3}},
                                      {{40, 0}, {16, 0}},    {{41, 0}, {1, 1}},
                                      {{80, 0}, {2, 65536}}, {{81, 0}, {0, 15}}};
  const std::vector<CellUpdate> other{{{0, 0}, {0, 1}},  {{1, 0}, {2, 0}},  {{40, 0}, {0, 4}},
                                      {{41, 0}, {3, 0}}, {{80, 0}, {1, 0}}, {{81, 0}, {7, 0}}};
  f.Change(mixed, true);
  f.index.Track(0, mixed, GainOfAdded(mixed, f.after));
  ASSERT_EQ(f.index.Gain(0), f.map.QuantizedGain(mixed));
  for (int round = 0; round < 3; ++round) {
    f.Change(other, true);
    EXPECT_EQ(f.index.Gain(0), f.map.QuantizedGain(mixed)) << "round " << round;
  }
  f.Change(other, false);
  EXPECT_EQ(f.index.Gain(0), f.map.QuantizedGain(mixed));
  std::vector<CellUpdate> cells;
  f.index.Cells(0, &cells);
  ASSERT_EQ(cells.size(), mixed.size());
  for (std::size_t k = 0; k < cells.size(); ++k) {
    EXPECT_EQ(cells[k].cell, mixed[k].cell);
    EXPECT_EQ(cells[k].delta.hits, mixed[k].delta.hits);
    EXPECT_EQ(cells[k].delta.misses, mixed[k].delta.misses);
  }
}

// The gain of a scan just added, from the states its cells were left in, is the gain
// computed from the map.
TEST(GainIndex, TheGainOfAnAddedScanComesFromTheStatesItLeft) {
  Fixture f;
  const auto lists = RandomLists(f.map, 8, 5);
  for (const auto& list : lists) {
    f.Change(list, true);
    EXPECT_EQ(GainOfAdded(list, f.after), f.map.QuantizedGain(list));
  }
  f.Change(lists[0], true);  // the same scan twice: a cell of pure counts seen twice
  EXPECT_EQ(GainOfAdded(lists[0], f.after), f.map.QuantizedGain(lists[0]));
}

// Scans at places 60 m apart, tracked and untracked as the robot comes and goes, and changes
// that span two places at once (a list whose box holds far more chunks than are tracked):
// the index tells a change far from every tracked scan apart by a bound on their chunks, and
// no gain may go stale however that bound was grown or recomputed.
TEST(GainIndex, GainsStayExactAsTrackedScansComeAndGoFarApart) {
  Fixture f;
  const testing::World room = testing::RoomWorld();
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> x(0.5, 7.5), y(0.5, 4.5), theta(-3.1, 3.1);
  const std::vector<Pose2> places{{0, 0, 0}, {60, 0, 0}, {0, 60, 0}, {-60, 60, 0}};
  std::vector<std::vector<CellUpdate>> lists;
  for (int i = 0; i < 24; ++i) {
    const Pose2 pose(x(rng), y(rng), theta(rng));
    lists.push_back(f.map.TouchedCells(testing::SimulateScan(room, pose),
                                       places[static_cast<std::size_t>(i) % places.size()] * pose));
  }
  for (int i = 0; i < 6; ++i) {  // a list of two places' scans
    std::vector<CellUpdate> both = lists[static_cast<std::size_t>(2 * i)];
    const auto& other = lists[static_cast<std::size_t>(2 * i + 1)];
    both.insert(both.end(), other.begin(), other.end());
    std::sort(both.begin(), both.end(),
              [](const CellUpdate& a, const CellUpdate& b) { return RowOrder(a.cell, b.cell); });
    lists.push_back(std::move(both));
  }
  std::vector<bool> in_map(lists.size(), false);
  int checked = 0;
  for (int step = 0; step < 400; ++step) {
    const auto id = static_cast<NodeId>(rng() % lists.size());
    const auto i = static_cast<std::size_t>(id);
    if (f.index.Tracks(id)) {
      f.index.Untrack(id);
      if (rng() % 2 == 0) continue;  // it stays in the map, untracked
    }
    if (in_map[i] && rng() % 3 == 0) {
      f.index.Track(id, lists[i], f.map.QuantizedGain(lists[i]));
      continue;
    }
    f.Change(lists[i], !in_map[i]);
    in_map[i] = !in_map[i];
    if (in_map[i] && rng() % 2 == 0) {
      f.index.Track(id, lists[i], f.map.QuantizedGain(lists[i]));
    }
    for (NodeId n = 0; n < static_cast<NodeId>(lists.size()); ++n) {
      if (!f.index.Tracks(n)) continue;
      ASSERT_EQ(f.index.Gain(n), f.map.QuantizedGain(lists[n])) << "node " << n << " step " << step;
      ++checked;
    }
  }
  EXPECT_GT(checked, 500);
}

TEST(GainIndex, TrackingTwiceOrUntrackingAStrangerIsALogicError) {
  Fixture f;
  const auto lists = RandomLists(f.map, 1, 3);
  f.Change(lists[0], true);
  f.index.Track(4, lists[0], 17);
  EXPECT_THROW(f.index.Track(4, lists[0], 17), std::logic_error);
  EXPECT_THROW(f.index.Untrack(5), std::logic_error);
  EXPECT_EQ(f.index.Untrack(4), 17);
  EXPECT_FALSE(f.index.Tracks(4));
  EXPECT_THROW(f.index.Gain(4), std::logic_error);
}

// A cell that only two scans see, both as free space: removing one makes the other its only
// observer, whose gain then counts the cell's whole bit (from 0 to 1 bit unknown).
TEST(GainIndex, ASoleObserverLeftBehindGainsTheCell) {
  Fixture f;
  const std::vector<CellUpdate> a{{{3, 3}, {0, 1}}}, b{{{3, 3}, {0, 2}}};
  f.Change(a, true);
  f.Change(b, true);
  f.index.Track(1, a, f.map.QuantizedGain(a));
  EXPECT_EQ(f.index.Gain(1), 0);
  f.Change(b, false);
  EXPECT_EQ(f.index.Gain(1), f.map.QuantizedGain(a));
  EXPECT_EQ(f.index.Gain(1), QuantizedEntropy({0, 0}));
}

// A change meets the tracked chunk at the edge of its box, whichever way the index looks:
// through the chunks of the change's box (two scans tracked close together) or through the
// tracked chunks (two tracked far apart, so that their box holds far more chunks than they).
TEST(GainIndex, AChangeReachesATrackedChunkAtTheEdgeOfItsBox) {
  for (const int far : {40, 4000}) {
    Fixture f;
    const std::vector<CellUpdate> a{{{3, 3}, {0, 1}}}, c{{{far, far}, {0, 1}}};
    const std::vector<CellUpdate> b{{{3, 3}, {0, 2}}, {{far / 2, far / 2}, {1, 0}}};
    for (const auto* list : {&a, &b, &c}) f.Change(*list, true);
    f.index.Track(1, a, f.map.QuantizedGain(a));
    f.index.Track(2, c, f.map.QuantizedGain(c));
    f.Change(b, false);
    EXPECT_EQ(f.index.Gain(1), QuantizedEntropy({0, 0})) << "far " << far;
  }
}

TEST(ChunkedCells, GroupsByChunkInBitOrderAndRefusesAnUnorderedList) {
  // Rows 31 and 32 straddle a band; x = -1 and 0 straddle a chunk column.
  const std::vector<CellUpdate> cells{{{-1, 31}, {0, 1}},
                                      {{0, 31}, {0, 1}},
                                      {{5, 31}, {1, 0}},
                                      {{-1, 32}, {0, 1}},
                                      {{3, 32}, {0, 1}}};
  ChunkedCells grouped;
  grouped.Assign(cells);
  ASSERT_EQ(grouped.chunks.size(), 4u);
  EXPECT_EQ(grouped.order, (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
  const ChunkedCells::Chunk& second = grouped.chunks[1];  // chunk (0, 0): (0, 31) and (5, 31)
  EXPECT_EQ(second.first, 1u);
  EXPECT_EQ(second.count, 2u);
  EXPECT_EQ(second.bits[(31 * 32) / 64],
            (std::uint64_t{1} << (31 * 32) % 64) | (std::uint64_t{1} << (31 * 32 + 5) % 64));
  std::vector<CellUpdate> swapped = cells;
  std::swap(swapped[1], swapped[2]);
  EXPECT_THROW(grouped.Assign(swapped), std::invalid_argument);
  std::vector<CellUpdate> twice = cells;
  twice[1] = twice[0];
  EXPECT_THROW(grouped.Assign(twice), std::invalid_argument);
}

TEST(GridMapLists, CountTheListsTouchingACellAndSurviveAFailedRemove) {
  GridMap map;
  const CellIndex c{-40, 7};
  map.Add({{c, {1, 0}}});
  map.Add({{c, {0, 3}}, {{0, 0}, {0, 1}}});
  map.Add({{c, {0, 0}}});  // touches nothing
  EXPECT_EQ(map.Lists(c), 2u);
  EXPECT_EQ(map.Lists({0, 0}), 1u);
  std::vector<CellState> after;
  map.Remove({{c, {1, 0}}}, &after);
  ASSERT_EQ(after.size(), 1u);
  EXPECT_EQ(after[0].lists, 1u);
  EXPECT_EQ(after[0].counts.misses, 3u);
  EXPECT_THROW(map.Remove({{{0, 0}, {0, 1}}, {c, {0, 9}}}), std::logic_error);
  EXPECT_EQ(map.Lists({0, 0}), 1u);
  EXPECT_EQ(map.Lists(c), 1u);
}

}  // namespace
}  // namespace lifelong::slam
