// Map blur and entropy on synthetic maps built from known walls (res 0.1 m).
#include "eval/metrics/map_quality.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace lifelong::eval {
namespace {

constexpr double kRes = 0.1;
constexpr double kPi = 3.14159265358979323846;

// Two parallel 10 m walls 3 m apart, on cell centres: 101 raster cells each.
std::vector<Segment> Corridor() { return {{0.05, 0.05, 10.05, 0.05}, {0.05, 3.05, 10.05, 3.05}}; }

OccupancyGrid Perfect() { return RasterizeWalls(Corridor(), kRes); }

/// Copies every occupied cell k cells up and down (thickening).
OccupancyGrid Thicken(const OccupancyGrid& g, int k) {
  OccupancyGrid out = g;
  for (int r = 0; r < g.height; ++r)
    for (int c = 0; c < g.width; ++c)
      if (g.At(c, r) >= 0.65f)
        for (int d = -k; d <= k; ++d) out.At(c, r + d) = 1.0f;
  return out;
}

TEST(BlurTest, PerfectMapScoresZero) {
  const BlurResult b = ComputeBlur(Perfect(), Corridor(), Pose2(), {});
  EXPECT_EQ(b.occupied_cells, 202u);
  EXPECT_LT(b.mean_cm, 0.5 * kRes * 100);
  EXPECT_LT(b.p95_cm, 0.5 * kRes * 100);
  EXPECT_DOUBLE_EQ(b.recall, 1.0);
  EXPECT_NEAR(b.wall_length_m, 20.0, 1e-9);
  EXPECT_NEAR(b.thickness, 1.0 / kRes, 0.02 / kRes);  // 202 cells / 20 m
}

TEST(BlurTest, ShiftedWallsScoreTheShiftAndTheAlignmentUndoesIt) {
  OccupancyGrid shifted = Perfect();
  shifted.origin_y_m += 0.3;  // every wall 3 cells up
  const BlurResult b = ComputeBlur(shifted, Corridor(), Pose2(), {});
  EXPECT_NEAR(b.mean_cm, 30.0, 1e-3);
  EXPECT_NEAR(b.p95_cm, 30.0, 1e-3);
  EXPECT_DOUBLE_EQ(b.recall, 0.0);  // 3 cells away > 1.5-cell tolerance
  const BlurResult aligned = ComputeBlur(shifted, Corridor(), Pose2(0, -0.3, 0), {});
  EXPECT_LT(aligned.mean_cm, 0.5 * kRes * 100);
  EXPECT_DOUBLE_EQ(aligned.recall, 1.0);
}

TEST(BlurTest, RotatedMapIsScoredInTheTrueFrame) {
  std::vector<Segment> rotated;  // the corridor turned by +90 deg: (x, y) -> (-y, x)
  for (const Segment& s : Corridor()) rotated.push_back({-s.y0, s.x0, -s.y1, s.x1});
  const OccupancyGrid map = RasterizeWalls(rotated, kRes);
  const BlurResult b = ComputeBlur(map, Corridor(), Pose2(0, 0, -kPi / 2), {});
  EXPECT_LT(b.mean_cm, 0.5 * kRes * 100);
  EXPECT_GT(b.recall, 0.95);
  EXPECT_GT(ComputeBlur(map, Corridor(), Pose2(), {}).mean_cm, 100.0);  // unaligned: far off
}

TEST(BlurTest, ThickenedWallsScoreThicknessAndMeanOffset) {
  for (int k : {1, 2}) {
    const BlurResult b = ComputeBlur(Thicken(Perfect(), k), Corridor(), Pose2(), {});
    EXPECT_NEAR(b.thickness, (2 * k + 1) / kRes, 0.02 * (2 * k + 1) / kRes) << k;
    // offsets 0, 1..k on both sides, in cells: mean k(k+1)/(2k+1)
    EXPECT_NEAR(b.mean_cm, k * (k + 1.0) / (2 * k + 1) * kRes * 100, 1e-3) << k;
    EXPECT_NEAR(b.p95_cm, k * kRes * 100, 1e-3) << k;
    EXPECT_DOUBLE_EQ(b.recall, 1.0);
  }
}

TEST(BlurTest, RecallDropsWhenWallsAreMissing) {
  OccupancyGrid map = Perfect();
  for (int r = 0; r < map.height; ++r)
    for (int c = 0; c < map.width; ++c)
      if (map.origin_y_m + r * kRes > 1.0 && map.origin_x_m + c * kRes < 5.0) map.At(c, r) = 0.0f;
  const BlurResult b = ComputeBlur(map, Corridor(), Pose2(), {});
  // top wall cells x = 0.05..4.95 (50) are gone; the one next to x = 5.05 is within 1.5 cells
  EXPECT_EQ(b.wall_cells, 202u);
  EXPECT_EQ(b.wall_cells_recalled, 202u - 49u);
}

TEST(BlurTest, RecallOnlyCountsWallsInRangeOfTheTrajectory) {
  OccupancyGrid map = Perfect();
  for (int r = 0; r < map.height; ++r)
    for (int c = 0; c < map.width; ++c)
      if (map.origin_y_m + r * kRes > 1.0) map.At(c, r) = 0.0f;  // top wall never mapped
  const std::vector<Pose2> along_bottom = {{0.05, 0.55, 0}, {10.05, 0.55, 0}};
  BlurConfig config;
  config.visibility_range_m = 1.0;  // the top wall is 2.5 m from the path
  const BlurResult b = ComputeBlur(map, Corridor(), Pose2(), along_bottom, config);
  EXPECT_EQ(b.wall_cells, 101u);
  EXPECT_DOUBLE_EQ(b.recall, 1.0);
  EXPECT_NEAR(b.wall_length_m, 10.0, 1e-9);
  EXPECT_LT(ComputeBlur(map, Corridor(), Pose2(), {}).recall, 0.51);  // all walls: half
}

TEST(EntropyTest, SumsBinaryEntropyOfKnownCellsOnly) {
  OccupancyGrid g;
  g.width = 5, g.height = 1;
  g.p_occ = {OccupancyGrid::kUnknown, 0.5f, 1.0f, 0.0f, 0.25f};
  const EntropyResult e = ComputeMapEntropy(g);
  // H(0.5) = 1, H(1) = H(0) = 0, H(0.25) = 0.25*2 + 0.75*log2(4/3) = 0.811278 bits
  EXPECT_NEAR(e.entropy_bits, 1.0 + 0.5 + 0.75 * std::log2(4.0 / 3.0), 1e-6);
  EXPECT_EQ(e.known_cells, 4u);
  EXPECT_EQ(e.occupied_cells, 1u);
  EXPECT_DOUBLE_EQ(e.occupied_share, 0.25);
}

}  // namespace
}  // namespace lifelong::eval
