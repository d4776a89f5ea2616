// Counting grid map (seed eq. 3.10), entropy and information gain (seed eqs. 5.10, 5.11).
#include "slam/grid/grid_map.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/slam/synthetic_scans.hpp"

namespace lifelong::slam {
namespace {

using CountMap = std::map<std::pair<int, int>, std::pair<std::uint32_t, std::uint32_t>>;

CountMap Snapshot(const GridMap& map) {
  CountMap out;
  map.ForEachKnownCell([&out](CellIndex c, CellCounts n) { out[{c.x, c.y}] = {n.hits, n.misses}; });
  return out;
}

// One beam along +x from the centre of cell (0, 0).
LaserScan OneBeam(float range_m, double range_max_m = 10.0) {
  LaserScan scan;
  scan.range_max_m = range_max_m;
  scan.ranges_m = {range_m};
  return scan;
}

const Pose2 kCellCentre(0.025, 0.025, 0.0);

TEST(GridMapTest, OneReturnMissesAlongTheBeamAndHitsAtTheEnd) {
  GridMap map;
  // End point x = 0.025 + 0.26 = 0.285 m: cell 5 (0.25..0.30).
  const std::vector<CellUpdate> cells = map.TouchedCells(OneBeam(0.26f), kCellCentre);
  ASSERT_EQ(cells.size(), 6u);
  for (int x = 0; x < 6; ++x) {
    EXPECT_EQ(cells[static_cast<std::size_t>(x)].cell, (CellIndex{x, 0}));
    EXPECT_EQ(cells[static_cast<std::size_t>(x)].delta.hits, x == 5 ? 1u : 0u);
    EXPECT_EQ(cells[static_cast<std::size_t>(x)].delta.misses, x == 5 ? 0u : 1u);
  }
  map.AddScan(OneBeam(0.26f), kCellCentre);
  EXPECT_DOUBLE_EQ(map.Probability({5, 0}), 1.0);
  EXPECT_DOUBLE_EQ(map.Probability({2, 0}), 0.0);
  EXPECT_DOUBLE_EQ(map.Probability({6, 0}), 0.5);
  EXPECT_FALSE(map.IsKnown({0, 1}));
  const CellBounds b = map.Bounds();
  ASSERT_FALSE(b.empty);
  EXPECT_EQ(b.min, (CellIndex{0, 0}));
  EXPECT_EQ(b.max, (CellIndex{5, 0}));
}

// A beam cut where an object now stands across it (BeamCut::resume_m): free up to short of
// the object, nothing about it, and again free beyond it up to its return, which it keeps.
TEST(GridMapTest, ACutBeamResumesBeyondTheObjectWithItsReturn) {
  GridMap map;
  // Ends at x = 0.325 (cell 6), 0.625 (cell 12) and 1.025 (cell 20).
  const std::vector<CellUpdate> cells =
      map.TouchedCells(OneBeam(1.0f), kCellCentre, {{0, 0.3f, 0.6f}});
  std::map<int, CellCounts> at;
  for (const CellUpdate& c : cells) at[c.cell.x] = c.delta;
  for (int x = 0; x <= 20; ++x) {
    const bool about_object = x >= 7 && x <= 11;
    ASSERT_EQ(at.count(x), about_object ? 0u : 1u) << "cell " << x;
    if (about_object) continue;
    EXPECT_EQ(at[x].hits, x == 20 ? 1u : 0u) << "cell " << x;
    EXPECT_EQ(at[x].misses, x == 20 ? 0u : 1u) << "cell " << x;
  }
  // Without resume_m the beam ends at free_to_m and its return is gone.
  const std::vector<CellUpdate> ended = map.TouchedCells(OneBeam(1.0f), kCellCentre, {{0, 0.3f}});
  ASSERT_EQ(ended.size(), 7u);
  for (const CellUpdate& c : ended) EXPECT_EQ(c.delta.hits, 0u);
}

TEST(GridMapTest, NoReturnAddsMissesUpToMaxFreeRange) {
  GridMapConfig config;
  config.max_free_range_m = 0.5;  // end x = 0.525: cell 10
  GridMap map(config);
  map.AddScan(OneBeam(10.0f, 10.0), kCellCentre);
  EXPECT_EQ(map.NumKnownCells(), 11u);
  for (int x = 0; x <= 10; ++x) {
    EXPECT_EQ(map.Hits({x, 0}), 0u);
    EXPECT_EQ(map.Misses({x, 0}), 1u);
  }
}

// A return beyond the usable range only clears space, like a "no return" beam.
TEST(GridMapTest, FarReturnOnlyClearsUpToMaxFreeRange) {
  GridMapConfig config;
  config.max_hit_range_m = 0.3;
  config.max_free_range_m = 0.2;  // end x = 0.225: cell 4
  GridMap map(config);
  map.AddScan(OneBeam(0.4f, 10.0), kCellCentre);  // a return at 0.4 m > 0.3 m
  EXPECT_EQ(map.NumKnownCells(), 5u);
  for (int x = 0; x <= 4; ++x) EXPECT_EQ(map.Hits({x, 0}), 0u);
  map.AddScan(OneBeam(0.26f, 10.0), kCellCentre);  // within range: a hit in cell 5
  EXPECT_EQ(map.Hits({5, 0}), 1u);
}

// Beams all along +x (zero field of view) from cell (0, 0)'s centre, range_max 10 m.
LaserScan BeamsAlongX(std::vector<float> ranges_m) {
  LaserScan scan;
  scan.range_max_m = 10.0;
  scan.ranges_m = std::move(ranges_m);
  return scan;
}

// A "no return" beam between two returns from a wall 0.26 m away is a dropout: it clears
// space up to one cell short of the wall, never through it (the hall scenario's 1 % dropout
// kept every scan's information gain above the threshold through such rays).
TEST(GridMapTest, DropoutBetweenReturnsStopsShortOfTheWall) {
  GridMapConfig config;
  config.max_free_range_m = 0.5;  // open space would be cleared to cell 10
  GridMap map(config);
  map.AddScan(BeamsAlongX({0.26f, 10.0f, 0.26f}), kCellCentre);
  EXPECT_EQ(map.Hits({5, 0}), 2u);
  EXPECT_EQ(map.Misses({5, 0}), 0u);  // the dropout did not cross the wall cell...
  for (int x = 6; x <= 10; ++x) EXPECT_FALSE(map.IsKnown({x, 0})) << x;  // ...nor behind it
  EXPECT_EQ(map.Misses({3, 0}), 3u);  // in front of the wall: all three beams

  // Off, a run longer than max_dropout_beams, or no return at all: open space, cleared to
  // max_free_range_m.
  for (const auto& [run, scan] : {std::pair{0, BeamsAlongX({0.26f, 10.0f, 0.26f})},
                                  std::pair{1, BeamsAlongX({0.26f, 10.0f, 10.0f, 0.26f})},
                                  std::pair{2, BeamsAlongX({10.0f, 10.0f, 10.0f})}}) {
    config.max_dropout_beams = run;
    GridMap open(config);
    open.AddScan(scan, kCellCentre);
    EXPECT_GE(open.Misses({8, 0}), 1u) << run;
  }
  // The scan's last beam lost: the return beside it bounds it.
  config.max_dropout_beams = 2;
  GridMap edge(config);
  edge.AddScan(BeamsAlongX({0.26f, 0.26f, 10.0f}), kCellCentre);
  EXPECT_EQ(edge.Misses({5, 0}), 0u);
  EXPECT_FALSE(edge.IsKnown({6, 0}));
}

TEST(GridMapTest, CountsAccumulateAndProbabilityIsTheirRatio) {
  GridMap map;
  map.AddScan(OneBeam(0.26f), kCellCentre);  // cell 5: hit
  map.AddScan(OneBeam(0.36f), kCellCentre);  // cell 5: miss, cell 7: hit
  map.AddScan(OneBeam(0.36f), kCellCentre);
  map.AddScan(OneBeam(0.36f), kCellCentre);
  EXPECT_EQ(map.Hits({5, 0}), 1u);
  EXPECT_EQ(map.Misses({5, 0}), 3u);
  EXPECT_DOUBLE_EQ(map.Probability({5, 0}), 0.25);
  // H(0.25) = -0.25 log2 0.25 - 0.75 log2 0.75.
  EXPECT_NEAR(CellEntropyBits(map.Counts({5, 0})), 0.5 + 0.75 * std::log2(4.0 / 3.0), 1e-12);
}

TEST(GridMapTest, EntropyOfARegionByHand) {
  GridMap map;
  const CellBounds region{{0, 0}, {9, 9}, false};  // 100 cells
  EXPECT_DOUBLE_EQ(map.EntropyBits(region), 100.0);
  map.AddScan(OneBeam(0.26f), kCellCentre);  // six cells become certain
  EXPECT_DOUBLE_EQ(map.EntropyBits(region), 94.0);
  map.AddScan(OneBeam(0.36f), kCellCentre);  // cell 5 now 1 hit / 1 miss; cells 6, 7 known
  EXPECT_DOUBLE_EQ(map.EntropyBits(region), 93.0);
}

TEST(GridMapTest, AddThenRemoveRestoresCountsExactly) {
  const testing::World room = testing::RoomWorld();
  GridMap map;
  const Pose2 a(2.0, 3.0, 0.3), b(5.0, 2.0, 2.0), c(4.0, 1.5, -1.0);
  map.AddScan(testing::SimulateScan(room, a), a);
  map.AddScan(testing::SimulateScan(room, b), b);
  const CountMap before = Snapshot(map);
  const LaserScan scan_c = testing::SimulateScan(room, c);
  map.AddScan(scan_c, c);
  EXPECT_NE(Snapshot(map), before);
  map.RemoveScan(scan_c, c);
  EXPECT_EQ(Snapshot(map), before);
  // Removing it again fails, and leaves every count as it was (all or nothing).
  EXPECT_THROW(map.RemoveScan(scan_c, c), std::logic_error);
  EXPECT_EQ(Snapshot(map), before);
  // A list naming a cell twice, each entry within the counts but not both together.
  const CellIndex cell{40, 60};
  map.Add({{cell, {0, 1}}});
  const CountMap with_one = Snapshot(map);
  const CellCounts n = map.Counts(cell);
  EXPECT_THROW(map.Remove({{cell, {0, 1}}, {cell, n}}), std::logic_error);
  EXPECT_EQ(Snapshot(map), with_one);
}

// Add, Remove and InformationGain look chunks up once per run of cells in one chunk row;
// any order of the list (runs cut short, chunk and sign boundaries crossed) must give what
// the ordered list gives.
TEST(GridMapTest, UpdateListsInAnyOrderGiveTheSameCountsAndGain) {
  const testing::World room = testing::RoomWorld();
  const Pose2 a(2.0, 3.0, 0.3), b(5.0, 2.0, 2.0);
  GridMap sorted_map, shuffled_map;
  const Pose2 shift(-4.0, -2.5, 0.0);  // the room straddles cell 0 in x and y
  std::vector<CellUpdate> first =
      sorted_map.TouchedCells(testing::SimulateScan(room, a), shift * a);
  const std::vector<CellUpdate> second =
      sorted_map.TouchedCells(testing::SimulateScan(room, b), shift * b);
  sorted_map.Add(first);
  sorted_map.Add(second);
  std::vector<CellUpdate> shuffled = first;
  std::mt19937 rng(3);
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  shuffled_map.Add(second);
  shuffled_map.Add(shuffled);
  EXPECT_EQ(Snapshot(shuffled_map), Snapshot(sorted_map));
  EXPECT_NEAR(shuffled_map.InformationGain(shuffled), sorted_map.InformationGain(first), 1e-9);
  shuffled_map.Remove(shuffled);
  sorted_map.Remove(first);
  EXPECT_EQ(Snapshot(shuffled_map), Snapshot(sorted_map));
}

TEST(GridMapTest, MoveScanEqualsAddingAtTheNewPose) {
  const testing::World room = testing::RoomWorld();
  const Pose2 a(2.0, 3.0, 0.3), wrong(2.3, 2.8, 0.5);
  const LaserScan scan = testing::SimulateScan(room, a);
  GridMap moved, direct;
  moved.AddScan(scan, wrong);
  moved.MoveScan(scan, wrong, a);
  direct.AddScan(scan, a);
  EXPECT_EQ(Snapshot(moved), Snapshot(direct));
}

// Every known cell's counts and lists.
std::map<std::pair<int, int>, std::vector<std::uint32_t>> States(const GridMap& map) {
  std::map<std::pair<int, int>, std::vector<std::uint32_t>> out;
  map.ForEachKnownCell([&](CellIndex c, CellCounts n) {
    out[{c.x, c.y}] = {n.hits, n.misses, map.Lists(c)};
  });
  return out;
}

// Move leaves the counts and lists that Remove then Add leave, reports the state of every
// cell of the new list and exactly the cells whose state changed, and skips the cells whose
// increment is the same at both poses (most of a small move's).
TEST(GridMapTest, MoveEqualsRemovingThenAddingAndReportsWhatChanged) {
  const testing::World room = testing::RoomWorld();
  const Pose2 shift(-4.0, -2.5, 0.0);  // cells on both sides of 0
  const Pose2 a(2.0, 3.0, 0.3), b(5.0, 2.0, 2.0), a_moved(2.02, 2.99, 0.304);
  GridMap moved, direct;
  const LaserScan scan = testing::SimulateScan(room, a);
  const std::vector<CellUpdate> other =
      moved.TouchedCells(testing::SimulateScan(room, b), shift * b);
  const std::vector<CellUpdate> from = moved.TouchedCells(scan, shift * a);
  const std::vector<CellUpdate> to = moved.TouchedCells(scan, shift * a_moved);
  for (GridMap* map : {&moved, &direct}) {
    map->Add(other);
    map->Add(from);
  }
  const auto before = States(moved);
  std::vector<CellState> after, after_direct;
  std::vector<CellChange> changed;
  moved.Move(from, to, &after, &changed);
  direct.Remove(from);
  direct.Add(to, &after_direct);
  EXPECT_EQ(States(moved), States(direct));
  ASSERT_EQ(after.size(), to.size());
  for (std::size_t i = 0; i < to.size(); ++i) {
    EXPECT_EQ(after[i].counts.hits, after_direct[i].counts.hits);
    EXPECT_EQ(after[i].counts.misses, after_direct[i].counts.misses);
    EXPECT_EQ(after[i].lists, after_direct[i].lists);
  }
  // Cells left with no counts are unknown again: absent from the states.
  const auto now = States(moved);
  const auto state = [](const auto& states, const std::pair<int, int>& cell) {
    const auto it = states.find(cell);
    return it == states.end() ? std::vector<std::uint32_t>{0, 0, 0} : it->second;
  };
  std::size_t differ = 0;
  for (const auto* states : {&now, &before}) {
    for (const auto& [cell, unused] : *states) {
      const bool other_has = (states == &now ? before : now).count(cell) != 0;
      if (states == &before && other_has) continue;  // counted once, from `now`
      differ += state(before, cell) != state(now, cell) ? 1 : 0;
    }
  }
  EXPECT_EQ(changed.size(), differ);
  for (std::size_t i = 0; i < changed.size(); ++i) {
    const CellChange& c = changed[i];
    EXPECT_EQ(
        state(now, {c.cell.x, c.cell.y}),
        (std::vector<std::uint32_t>{c.after.counts.hits, c.after.counts.misses, c.after.lists}));
    EXPECT_EQ(
        state(before, {c.cell.x, c.cell.y}),
        (std::vector<std::uint32_t>{c.before.counts.hits, c.before.counts.misses, c.before.lists}));
    if (i > 0) {
      const CellIndex prev = changed[i - 1].cell;
      EXPECT_TRUE(prev.y < c.cell.y || (prev.y == c.cell.y && prev.x < c.cell.x));
    }
  }
  EXPECT_GT(differ, 0u);
  EXPECT_LT(differ, from.size());  // a small move keeps many cells' increments
}

// A list that was never added, or one out of order, leaves the map as it was.
TEST(GridMapTest, MoveIsAllOrNothing) {
  const testing::World room = testing::RoomWorld();
  const Pose2 a(2.0, 3.0, 0.3), b(5.0, 2.0, 2.0);
  GridMap map;
  const std::vector<CellUpdate> in_map = map.TouchedCells(testing::SimulateScan(room, a), a);
  const std::vector<CellUpdate> stranger = map.TouchedCells(testing::SimulateScan(room, b), b);
  map.Add(in_map);
  const auto before = States(map);
  EXPECT_THROW(map.Move(stranger, in_map), std::logic_error);
  EXPECT_EQ(States(map), before);
  std::vector<CellUpdate> unordered = stranger;
  std::swap(unordered[10], unordered[20]);
  EXPECT_THROW(map.Move(in_map, unordered), std::invalid_argument);
  EXPECT_EQ(States(map), before);
  map.Move(in_map, stranger);
  map.Move(stranger, in_map);
  EXPECT_EQ(States(map), before);
}

TEST(GridMapTest, NegativeCellIndicesWork) {
  GridMap map;
  map.AddScan(OneBeam(0.26f), Pose2(-0.025, -0.025, 3.14159265358979323846));
  // From the centre of cell (-1, -1) towards -x: end x = -0.285, cell -6.
  EXPECT_EQ(map.Hits({-6, -1}), 1u);
  EXPECT_EQ(map.Misses({-1, -1}), 1u);
  EXPECT_EQ(map.Bounds().min, (CellIndex{-6, -1}));
}

TEST(GridMapTest, GainOfTheOnlyScanIsOneBitPerTouchedCell) {
  const testing::World room = testing::RoomWorld();
  const Pose2 a(2.0, 3.0, 0.3);
  const LaserScan scan = testing::SimulateScan(room, a);
  GridMap map;
  map.AddScan(scan, a);
  // Every touched cell goes from unknown (1 bit) to hits-only or misses-only (0 bits) unless
  // the scan itself both hit and missed it.
  double expected = 0.0;
  for (const CellUpdate& u : map.TouchedCells(scan, a)) expected += 1.0 - CellEntropyBits(u.delta);
  EXPECT_GT(expected, 100.0);
  EXPECT_NEAR(map.InformationGain(scan, a), expected, 1e-9);
}

TEST(GridMapTest, RepeatedScanHasZeroGain) {
  const testing::World room = testing::RoomWorld();
  const Pose2 a(2.0, 3.0, 0.3);
  const LaserScan scan = testing::SimulateScan(room, a);
  GridMap map;
  map.AddScan(scan, a);
  map.AddScan(scan, a);
  map.AddScan(scan, a);
  // Removing one of three identical copies leaves every p(occ) unchanged.
  EXPECT_NEAR(map.InformationGain(scan, a), 0.0, 1e-12);
}

// The room seen densely from a 3 x 3 grid of poses (360 deg scans): the interior is known.
GridMap DenseRoomMap(const testing::World& room) {
  GridMap map;
  for (double x : {1.5, 4.0, 7.0}) {
    for (double y : {0.7, 2.5, 4.5}) {
      const Pose2 p(x, y, 0.0);
      map.AddScan(testing::SimulateScan(room, p, 721, 2.0 * 3.14159265358979323846), p);
    }
  }
  return map;
}

TEST(GridMapTest, MisalignedCopyHasNegativeGain) {
  // Seed §5.1: an observation that disagrees with former ones raises the entropy. A copy of
  // a scan facing the x = 8 wall, displaced 0.3 m back and turned 3 deg, puts its end points
  // into known free space (the map knows the interior densely).
  const testing::World room = testing::RoomWorld();
  GridMap map = DenseRoomMap(room);
  const Pose2 truth(5.0, 2.5, 0.0);
  const LaserScan scan = testing::SimulateScan(room, truth);
  const Pose2 misaligned = truth * Pose2(-0.3, 0.0, 3.0 * 3.14159265358979323846 / 180.0);
  map.AddScan(scan, misaligned);
  const double misaligned_gain = map.InformationGain(scan, misaligned);
  EXPECT_LT(misaligned_gain, 0.0);
  map.MoveScan(scan, misaligned, truth);
  EXPECT_GT(map.InformationGain(scan, truth), misaligned_gain);
}

// The gain's per-cell entropies come from a table for small counts and are summed in whole
// quanta: each must be the cell's binary entropy to within its quantum, table or not.
TEST(QuantizedEntropy, IsTheCellEntropyToItsQuantum) {
  for (std::uint32_t h : {0u, 1u, 2u, 3u, 7u, 63u, 64u, 100u, 4095u, 4096u, 5000u, 123456u}) {
    for (std::uint32_t m : {0u, 1u, 5u, 63u, 64u, 4000u, 4097u, 99999u}) {
      const CellCounts c{h, m};
      EXPECT_EQ(QuantizedEntropy(c), QuantizedEntropyOf(c));
      EXPECT_NEAR(static_cast<double>(QuantizedEntropy(c)) * kEntropyQuantumBits,
                  CellEntropyBits(c), 1e-11)
          << h << " hits, " << m << " misses";
    }
  }
}

}  // namespace
}  // namespace lifelong::slam
