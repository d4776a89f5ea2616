// scan_cells (eval/truth/scan_cells.hpp): the same scans at poses that agree cover fewer
// cells than at poses that do not.
#include "eval/truth/scan_cells.hpp"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace lifelong::eval {
namespace {

// A scan of a wall 2 m ahead, straight across, from a robot facing +x.
Observation WallScan() {
  Observation o;
  o.scan.angle_min_rad = -0.5;
  o.scan.angle_increment_rad = 0.01;
  o.scan.range_max_m = 30.0;
  for (int i = 0; i <= 100; ++i) {
    const double a = o.scan.angle_min_rad + 0.01 * i;
    o.scan.ranges_m.push_back(static_cast<float>(2.0 / std::cos(a)));
  }
  return o;
}

TEST(ScanCells, PosesThatAgreeCoverFewerCells) {
  const std::vector<Observation> stream = {WallScan(), WallScan()};
  const std::vector<std::size_t> both = {0, 1};
  const std::int64_t agree = ScanCells(stream, both, {Pose2(0, 0, 0), Pose2(0, 0, 0)}, 0.05, 12.0);
  const std::int64_t apart =
      ScanCells(stream, both, {Pose2(0, 0, 0), Pose2(0.3, 0, 0)}, 0.05, 12.0);
  const std::int64_t one = ScanCells(stream, {0}, {Pose2(0, 0, 0)}, 0.05, 12.0);
  EXPECT_EQ(agree, one);         // the second scan falls in the first's cells
  EXPECT_GT(apart, agree + 10);  // two walls 0.3 m apart
  // A turned pose smears the wall too; beyond max_range nothing is drawn.
  EXPECT_GT(ScanCells(stream, both, {Pose2(0, 0, 0), Pose2(0, 0, 0.1)}, 0.05, 12.0), agree);
  EXPECT_EQ(ScanCells(stream, both, {Pose2(0, 0, 0), Pose2(0, 0, 0)}, 0.05, 1.5), 0);
}

TEST(ScanCells, TheLaserMountIsApplied) {
  std::vector<Observation> stream = {WallScan(), WallScan()};
  stream[1].scan.T_robot_laser = Pose2(0.3, 0.0, 0.0);
  // The robot of scan 1 stands 0.3 m behind, its laser where scan 0's is.
  EXPECT_EQ(ScanCells(stream, {0, 1}, {Pose2(0, 0, 0), Pose2(-0.3, 0, 0)}, 0.05, 12.0),
            ScanCells(stream, {0}, {Pose2(0, 0, 0)}, 0.05, 12.0));
}

TEST(ScanCells, MismatchedInputIsRefused) {
  const std::vector<Observation> stream = {WallScan()};
  EXPECT_THROW(ScanCells(stream, {0}, {}, 0.05, 12.0), std::invalid_argument);
  EXPECT_THROW(ScanCells(stream, {0}, {Pose2()}, 0.0, 12.0), std::invalid_argument);
}

}  // namespace
}  // namespace lifelong::eval
