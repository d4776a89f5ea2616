// SurfacePoints (slam/matching/scan_matcher.hpp): a scan's returns joined into surfaces, and why
// the incremental matcher's local map uses them. Along an aisle whose shelf faces the beams hit at
// grazing angles, a likelihood field of the reference's returns alone is lumpy along the
// faces and pulls a match back towards the reference pose: motion is under-measured.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "slam/matching/scan_matcher.hpp"
#include "tests/slam/synthetic_scans.hpp"

namespace lifelong::slam {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// Beams from -bearing to +bearing (1 degree apart) at a wall x = d in front of the robot,
/// except those listed as misses.
LaserScan WallScan(double d, int half_beams, std::vector<int> misses = {}) {
  LaserScan scan;
  scan.range_max_m = 30.0;
  scan.angle_min_rad = -half_beams * kDeg;
  scan.angle_increment_rad = kDeg;
  for (int i = -half_beams; i <= half_beams; ++i) {
    const bool miss = std::find(misses.begin(), misses.end(), i) != misses.end();
    scan.ranges_m.push_back(miss ? 30.0f : static_cast<float>(d / std::cos(i * kDeg)));
  }
  return scan;
}

/// The points' y coordinates, ascending.
std::vector<double> SortedY(const std::vector<Eigen::Vector2d>& points) {
  std::vector<double> y;
  for (const Eigen::Vector2d& p : points) y.push_back(p.y());
  std::sort(y.begin(), y.end());
  return y;
}

double LargestStep(const std::vector<double>& sorted) {
  double step = 0.0;
  for (std::size_t i = 1; i < sorted.size(); ++i) step = std::max(step, sorted[i] - sorted[i - 1]);
  return step;
}

TEST(SurfacePoints, FillsTheWallBetweenReturnsAtTheThinningSpacing) {
  const LaserScan scan = WallScan(10.0, 10);  // returns ~0.18 m apart on the wall
  const std::vector<Eigen::Vector2d> returns = ScanToPoints(scan, 0.05);
  const std::vector<Eigen::Vector2d> surface = SurfacePoints(scan, 0.05, {0.3, 0.0});
  EXPECT_GT(LargestStep(SortedY(returns)), 0.17);
  // One point per 5 cm voxel: neighbours are less than two voxels apart.
  EXPECT_LT(LargestStep(SortedY(surface)), 0.1);
  for (const Eigen::Vector2d& p : surface) EXPECT_NEAR(p.x(), 10.0, 1e-4);
  const std::vector<double> y = SortedY(surface);
  EXPECT_NEAR(y.front(), -10.0 * std::tan(10 * kDeg), 0.05);
  EXPECT_NEAR(y.back(), 10.0 * std::tan(10 * kDeg), 0.05);
}

TEST(SurfacePoints, DoesNotJoinReturnsFartherApartThanTheGapOrAcrossAMiss) {
  const LaserScan scan = WallScan(10.0, 10, {0});
  const double half_step = 0.5 * 10.0 * std::tan(1 * kDeg);
  // Returns 0.175 m apart: a gap of 0.1 m keeps the returns alone.
  EXPECT_EQ(SurfacePoints(scan, 0.05, {0.1, 0.0}).size(), ScanToPoints(scan, 0.05).size());
  // The missing beam 0 leaves the wall open between beams -1 and 1.
  for (const Eigen::Vector2d& p : SurfacePoints(scan, 0.05, {0.3, 0.0})) {
    EXPECT_FALSE(std::abs(p.y()) < half_step) << p.y();
  }
}

TEST(SurfacePoints, NeedsAPositiveSpacing) {
  EXPECT_THROW(SurfacePoints(WallScan(2.0, 3), 0.0, {0.3}), std::invalid_argument);
}

// A wall 1 m to the side, along which the returns spread out to 1 m apart at 7 m.
TEST(SurfacePoints, TheLineRuleJoinsAWallHitAtAGrazingAngleBeyondTheGap) {
  const testing::World wall = {{0.0, 1.0, 8.0, 1.0}};
  const LaserScan scan = testing::SimulateScan(wall, Pose2());
  const auto wall_y = [](const std::vector<Eigen::Vector2d>& points) {
    std::vector<double> x;
    for (const Eigen::Vector2d& p : points) {
      EXPECT_NEAR(p.y(), 1.0, 1e-3);
      if (p.x() < 7.0) x.push_back(p.x());
    }
    std::sort(x.begin(), x.end());
    return x;
  };
  EXPECT_GT(LargestStep(wall_y(SurfacePoints(scan, 0.05, {0.3, 0.0}))), 0.6);
  EXPECT_LT(LargestStep(wall_y(SurfacePoints(scan, 0.05, {0.3, 1.5}))), 0.1);
}

// A post face 3 m ahead (y in [-1, 0]) in front of a wall 6 m ahead: the beams step from the
// face to the wall, and that step is no surface, however far the line rule may reach.
TEST(SurfacePoints, TheLineRuleDoesNotJoinADepthJump) {
  const testing::World scene = {{3.0, -1.0, 3.0, 0.0}, {6.0, -5.0, 6.0, 5.0}};
  const LaserScan scan = testing::SimulateScan(scene, Pose2());
  for (const SurfaceRule rule : {SurfaceRule{0.3, 5.0}, SurfaceRule{0.3, 5.0, 0.2}}) {
    const std::vector<Eigen::Vector2d> points = SurfacePoints(scan, 0.05, rule);
    int on_face = 0, on_wall = 0;
    for (const Eigen::Vector2d& p : points) {
      EXPECT_TRUE(std::abs(p.x() - 3.0) < 1e-3 || std::abs(p.x() - 6.0) < 1e-3) << p.transpose();
      (p.x() < 4.5 ? on_face : on_wall) += 1;
    }
    EXPECT_GT(on_face, 10);
    EXPECT_GT(on_wall, 100);
  }
}

// A wall the beams hit squarely, with 1 cm range noise: joined by the gap alone, as before, and
// the line rule adds nothing where the returns are close.
TEST(SurfacePoints, TheLineRuleLeavesCloseReturnsToTheGap) {
  LaserScan scan = WallScan(3.0, 20);
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    scan.ranges_m[i] += (i % 2 == 0 ? 0.01f : -0.01f);
  }
  EXPECT_EQ(SurfacePoints(scan, 0.05, {0.3, 0.0}).size(),
            SurfacePoints(scan, 0.05, {0.3, 2.0}).size());
}

// An aisle 2.6 m wide and 32 m long with a cross passage: the robot moves 0.5 m along it
// and the matcher starts from odometry 2 % long, as the simulated Pioneer's.
TEST(SurfacePoints, ASurfaceReferenceDoesNotShortenMotionAlongAnAisle) {
  testing::World aisle = {{-2, -1.3, 12, -1.3}, {15, -1.3, 30, -1.3}, {-2, 1.3, 12, 1.3},
                          {15, 1.3, 30, 1.3},   {30, -3, 30, 3},      {-2, -3, -2, 3},
                          {12, 1.3, 12, 2.5},   {15, 1.3, 15, 2.5},   {12, -1.3, 12, -2.5},
                          {15, -1.3, 15, -2.5}};
  MatcherConfig config;  // the incremental matcher's defaults
  config.linear_window_m = 0.3;
  config.angular_window_rad = 0.26;
  config.resolution_m = 0.03;
  config.sigma_m = 0.05;
  double points_bias = 0.0, surface_bias = 0.0, lines_bias = 0.0;
  int n = 0;
  for (double x = 1.0; x < 20.0; x += 0.37, ++n) {
    const auto pose = [](double at) { return Pose2(at, 0.1 * std::sin(at), 0.02 * std::cos(at)); };
    const Pose2 a = pose(x), b = pose(x + 0.5);
    const LaserScan scan_a = testing::SimulateScan(aisle, a),
                    scan_b = testing::SimulateScan(aisle, b);
    const Pose2 truth = Between(a, b), odometry(1.02 * truth.x, truth.y, truth.theta);
    const std::vector<Eigen::Vector2d> query = ScanToPoints(scan_b, 0.05);
    const MatchResult on_points =
        Match(ReferenceGrid(ScanToPoints(scan_a, 0.05), config), query, odometry, config);
    const MatchResult on_surface = Match(
        ReferenceGrid(SurfacePoints(scan_a, 0.05, {1.0, 0.0}), config), query, odometry, config);
    const MatchResult on_lines = Match(
        ReferenceGrid(SurfacePoints(scan_a, 0.05, {0.1, 2.0}), config), query, odometry, config);
    ASSERT_TRUE(on_points.ok && on_surface.ok && on_lines.ok);
    points_bias += (on_points.T_ref_cur.x - truth.x) / 0.5;
    surface_bias += (on_surface.T_ref_cur.x - truth.x) / 0.5;
    lines_bias += (on_lines.T_ref_cur.x - truth.x) / 0.5;
  }
  points_bias /= n;
  surface_bias /= n;
  lines_bias /= n;
  // Returns alone: about 7 % of the motion lost (measured -6.8 %).
  EXPECT_LT(points_bias, -0.04);
  // Surfaces: within 1 % (measured +0.2 %).
  EXPECT_LT(std::abs(surface_bias), 0.01);
  // A 0.1 m gap with the line rule: as close.
  EXPECT_LT(std::abs(lines_bias), 0.01) << lines_bias;
}

}  // namespace
}  // namespace lifelong::slam
