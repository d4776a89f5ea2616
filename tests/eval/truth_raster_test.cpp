// The truth raster a run makes once (issue #32) scores a map as the per-call rasterization
// does, also where the map reaches beyond the raster, and refuses a map at another resolution.
#include "eval/truth/truth_raster.hpp"

#include <stdexcept>

#include <gtest/gtest.h>

#include "eval/metrics/map_quality.hpp"

namespace lifelong::eval {
namespace {

constexpr double kRes = 0.1;

GroundTruth Corridor() {
  GroundTruth t;
  t.walls = {{0.05, 0.05, 10.05, 0.05}, {0.05, 3.05, 10.05, 3.05}, {5.05, 0.05, 5.05, 3.05}};
  t.walls_now = {t.walls[0], t.walls[1]};  // the cross wall (a door) opened
  t.gone = {t.walls[2]};
  return t;
}

TEST(TruthRaster, CoversTheSurfacesAndThePathWithAMargin) {
  const TruthRaster r(Corridor(), {{20.0, 1.0, 0.0}}, kRes);
  const Lattice& l = r.lattice();
  EXPECT_LE(l.ox, 0.05 - 1.0);
  EXPECT_GE(l.ox + l.cols * kRes, 20.0 + 1.0);  // the path beyond the walls is covered
  EXPECT_TRUE(r.walls().Holds(l.CellOf(5.05, 1.0)));
  EXPECT_FALSE(r.walls_now().Holds(l.CellOf(5.05, 1.0)));
  EXPECT_TRUE(r.gone().Holds(l.CellOf(5.05, 1.0)));
  EXPECT_NEAR(r.TrajectoryDistanceM(l.CellOf(20.0, 3.0)), 2.0, 1e-6);
  EXPECT_NEAR(r.walls().length_m(), 23.0, 1e-9);
}

TEST(TruthRaster, BeyondTheRasterTheDistanceIsTheExactOne) {
  const TruthRaster r(Corridor(), {}, kRes);
  const Lattice& l = r.lattice();
  const LatticeCell far = l.CellOf(30.05, 0.05);  // 20 m past the corridor's end, on its axis
  ASSERT_FALSE(l.Inside(far));
  EXPECT_NEAR(r.walls().DistanceCells(far), 200.0, 1e-6);
  EXPECT_NEAR(r.walls().DistanceCells(l.CellOf(2.05, 1.05)), 10.0, 1e-4);  // inside: the EDT
}

// A map with a wall 20 m off the truth: before the raster covered the map, each call's raster
// grew to hold it; now its cells lie off the run's raster and are scored exactly.
TEST(TruthRaster, AMapReachingBeyondTheRasterScoresAsBefore) {
  GroundTruth far = Corridor();
  far.walls.push_back({30.05, 0.05, 30.05, 2.05});
  const OccupancyGrid map = RasterizeWalls(far.walls, kRes);
  const TruthRaster r(Corridor(), {}, kRes);
  const BlurResult b = ComputeBlur(map, r, r.walls(), Pose2());
  const BlurResult perfect =
      ComputeBlur(RasterizeWalls(Corridor().walls, kRes), r, r.walls(), Pose2());
  // 21 cells of the far wall, each 20.0 .. 20.1 m (2000 .. 2010 cm, 200 .. 201 cells) off.
  EXPECT_EQ(b.occupied_cells, perfect.occupied_cells + 21u);
  EXPECT_NEAR(b.mean_cm * static_cast<double>(b.occupied_cells) -
                  perfect.mean_cm * static_cast<double>(perfect.occupied_cells),
              21.0 * 2000.0, 21.0 * 11.0);
  EXPECT_DOUBLE_EQ(b.recall, 1.0);
}

TEST(TruthRaster, ScoresAsTheOneCallRasterization) {
  const GroundTruth t = Corridor();
  OccupancyGrid map = RasterizeWalls(t.walls, kRes);
  map.origin_y_m += 0.2;  // two cells off
  const std::vector<Pose2> path = {{0.5, 1.5, 0.0}, {9.5, 1.5, 0.0}};
  const TruthRaster r(t, path, kRes);
  const BlurResult once = ComputeBlur(map, r, r.walls(), Pose2(0.0, -0.1, 0.0));
  const BlurResult each = ComputeBlur(map, t.walls, Pose2(0.0, -0.1, 0.0), path);
  EXPECT_EQ(once.occupied_cells, each.occupied_cells);
  EXPECT_DOUBLE_EQ(once.mean_cm, each.mean_cm);
  EXPECT_DOUBLE_EQ(once.recall, each.recall);
  EXPECT_DOUBLE_EQ(StaleShare(map, r, Pose2(0.0, -0.2, 0.0)),
                   StaleShare(map, t.gone, t.walls_now, Pose2(0.0, -0.2, 0.0)));
  EXPECT_GT(StaleShare(map, r, Pose2(0.0, -0.2, 0.0)), 0.0);  // the door's cells
}

TEST(TruthRaster, AMapAtAnotherResolutionIsRefused) {
  const TruthRaster r(Corridor(), {}, kRes);
  const OccupancyGrid coarse = RasterizeWalls(Corridor().walls, 2.0 * kRes);
  EXPECT_THROW(ComputeBlur(coarse, r, r.walls(), Pose2()), std::invalid_argument);
  EXPECT_THROW(StaleShare(coarse, r, Pose2()), std::invalid_argument);
}

TEST(TruthRaster, WallGridIsRasterizeWallsWhenThePathLiesWithin) {
  const GroundTruth t = Corridor();
  const OccupancyGrid a = TruthRaster(t, {{1.0, 1.0, 0.0}}, kRes).WallGrid();
  const OccupancyGrid b = RasterizeWalls(t.walls, kRes);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_DOUBLE_EQ(a.origin_x_m, b.origin_x_m);
  EXPECT_EQ(a.p_occ, b.p_occ);
}

}  // namespace
}  // namespace lifelong::eval
