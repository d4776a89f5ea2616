// A face seen at a grazing angle in the counting grid (GridMapConfig::hits_mask_own_misses).
#include <cmath>
#include <cstddef>
#include <vector>

#include <gtest/gtest.h>

#include "slam/grid/grid_map.hpp"
#include "tests/slam/synthetic_scans.hpp"

namespace lifelong::slam {
namespace {

// A wall along y = 1.01 from x = 0 to 8 seen from (0.2, 0.2), its far part at 6-14 deg: the
// beams to the wall's far end cross the wall's cells on their way to returns a little
// farther along.
struct Grazing {
  testing::World world{{0.0, 1.01, 8.0, 1.01}};
  Pose2 pose{0.2, 0.2, 0.0};
  LaserScan scan = testing::SimulateScan(world, pose, 361, M_PI, 30.0);
};

// The wall's cells (row y = 1.01 / 0.05 = 20) from x = 3 m on, where beams graze it: how
// many of those that a return fell in the map shows occupied (p >= 0.65).
struct WallCells {
  int hit = 0, shown = 0;
};
WallCells FarWall(const GridMap& map) {
  WallCells out;
  for (int x = 60; x < 160; ++x) {
    const CellIndex c{x, 20};
    if (map.Hits(c) == 0) continue;
    ++out.hit;
    out.shown += map.Probability(c) >= 0.65 ? 1 : 0;
  }
  return out;
}

TEST(GridGrazingTest, AScanDoesNotMissTheCellsItsOwnReturnsFellIn) {
  const Grazing g;
  GridMapConfig config;
  config.max_hit_range_m = 30.0;
  config.hits_mask_own_misses = false;
  GridMap counted(config);
  counted.AddScan(g.scan, g.pose);
  const WallCells before = FarWall(counted);
  ASSERT_GE(before.hit, 20);
  // Counted, the beams passing along the face outvote its returns in some of its cells.
  EXPECT_LT(before.shown, before.hit);

  config.hits_mask_own_misses = true;
  GridMap masked(config);
  masked.AddScan(g.scan, g.pose);
  const WallCells after = FarWall(masked);
  EXPECT_EQ(after.hit, before.hit);
  EXPECT_EQ(after.shown, after.hit);
  // Only the hit cells change: every cell the scan hit has no misses, every other cell keeps
  // the counts it had.
  for (const CellUpdate& u : masked.TouchedCells(g.scan, g.pose)) {
    if (u.delta.hits > 0) {
      EXPECT_EQ(u.delta.misses, 0u);
    } else {
      EXPECT_EQ(u.delta.misses, counted.Misses(u.cell));
    }
  }
  // The scan removed again leaves nothing behind.
  masked.RemoveScan(g.scan, g.pose);
  EXPECT_TRUE(masked.Bounds().empty);
}

// Returns on a face seen head-on are unchanged: no beam of the scan crosses a cell another
// beam of it ends in.
TEST(GridGrazingTest, AFaceSeenHeadOnIsTracedAsBefore) {
  const testing::World world{{2.01, -3.0, 2.01, 3.0}};
  const Pose2 pose{0.0, 0.02, 0.0};
  const LaserScan scan = testing::SimulateScan(world, pose, 31, 0.5, 30.0);
  GridMapConfig config;
  config.hits_mask_own_misses = false;
  const std::vector<CellUpdate> counted = GridMap(config).TouchedCells(scan, pose);
  config.hits_mask_own_misses = true;
  const std::vector<CellUpdate> masked = GridMap(config).TouchedCells(scan, pose);
  ASSERT_EQ(masked.size(), counted.size());
  for (std::size_t i = 0; i < masked.size(); ++i) {
    EXPECT_EQ(masked[i].cell, counted[i].cell);
    EXPECT_EQ(masked[i].delta.hits, counted[i].delta.hits);
    EXPECT_EQ(masked[i].delta.misses, counted[i].delta.misses);
  }
}

}  // namespace
}  // namespace lifelong::slam
