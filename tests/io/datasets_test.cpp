// The shared datasets as read by io (the counts of ../shared/datasets/SOURCES.md); skipped
// when the datasets are absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "io/carmen_log.hpp"
#include "io/relations.hpp"
#include "tests/io/io_test_util.hpp"

namespace lifelong::io {
namespace {

using namespace test_util;  // the io test helpers (tests/io/io_test_util.hpp)

bool HaveDatasets() { return Exists(kDatasets + "SOURCES.md"); }

/// Largest translation between consecutive scans' odometry poses.
double MaxStep(const CarmenLog& log) {
  double worst = 0.0;
  for (std::size_t i = 1; i < log.observations.size(); ++i) {
    const Pose2 d = Between(log.observations[i - 1].T_odom_robot, log.observations[i].T_odom_robot);
    worst = std::max(worst, std::hypot(d.x, d.y));
  }
  return worst;
}

TEST(Datasets, IntelRaw) {
  if (!HaveDatasets()) GTEST_SKIP() << "shared datasets absent: " << kDatasets;
  const CarmenLog log = ReadCarmenLog(kDatasets + "intel/intel-raw-first1088s.clf.gz");
  ASSERT_EQ(log.observations.size(), 5505u);
  EXPECT_TRUE(log.odometry.empty());
  EXPECT_FALSE(log.odometry_recovered);
  EXPECT_GT(log.backward_scan_stamps, 0);  // "a few timestamps run backwards"
  EXPECT_NEAR(log.observations.front().stamp_s, 0.000246, 1e-9);
  EXPECT_NEAR(log.observations.back().stamp_s, 1088.61, 0.01);
  EXPECT_NEAR(log.observations[0].scan.range_max_m, 81.83, 1e-5);
  EXPECT_EQ(log.observations[0].scan.ranges_m.size(), 180u);
  EXPECT_LT(MaxStep(log), 1.0);
}

void CheckCorrected(const std::string& file, std::size_t scans, std::size_t odom,
                    double range_max) {
  if (!HaveDatasets()) GTEST_SKIP() << "shared datasets absent: " << kDatasets;
  const CarmenLog log = ReadCarmenLog(kDatasets + file);
  EXPECT_TRUE(log.odometry_recovered);
  ASSERT_EQ(log.observations.size(), scans);
  EXPECT_EQ(log.skipped.at("NEFF"), static_cast<int>(scans));
  EXPECT_EQ(log.odometry.size() + static_cast<std::size_t>(log.dropped_odometry), odom);
  EXPECT_EQ(static_cast<std::size_t>(log.dropped_odometry), scans);
  EXPECT_NEAR(log.observations[0].scan.range_max_m, range_max, 1e-5);
  // Keyframes sit ~1 m apart (GMapping's linearUpdate), so allow 1.5 m, never a jump.
  EXPECT_LT(MaxStep(log), 1.5);
  // The raw steps differ from the corrected ones by GMapping's small corrections only.
  CarmenReadOptions off;
  off.recovery = OdometryRecovery::kOff;
  const CarmenLog corrected = ReadCarmenLog(kDatasets + file, off);
  int large = 0;
  for (std::size_t i = 1; i < scans; ++i) {
    const Pose2 raw =
        Between(log.observations[i - 1].T_odom_robot, log.observations[i].T_odom_robot);
    const Pose2 cor =
        Between(corrected.observations[i - 1].T_odom_robot, corrected.observations[i].T_odom_robot);
    large += std::hypot(raw.x - cor.x, raw.y - cor.y) > 0.2 ? 1 : 0;
  }
  EXPECT_LT(large, static_cast<int>(scans) / 20);
  // ... but they add up to a drift: raw odometry ends far from the corrected pose.
  const Pose2 end =
      Between(log.observations.back().T_odom_robot, corrected.observations.back().T_odom_robot);
  EXPECT_GT(std::hypot(end.x, end.y) + std::abs(end.theta), 0.5);
}

TEST(Datasets, IntelCorrected) {
  CheckCorrected("intel/intel-corrected.log.gz", 910, 14541, 81.83);
}
TEST(Datasets, FhwCorrected) { CheckCorrected("fhw/fhw-corrected.log.gz", 488, 13935, 51.10); }

TEST(Datasets, IntelRelations) {
  if (!HaveDatasets()) GTEST_SKIP() << "shared datasets absent: " << kDatasets;
  const auto rel = ReadRelations(kDatasets + "intel/intel.relations", kIntelRelationsTimeOffsetS);
  ASSERT_EQ(rel.size(), 2984u);
  EXPECT_NEAR(rel[0].t1_s, 976052905.167303 - 976052857.337284, 1e-6);
  ExpectPose(rel[0].T_1_2, -0.056990, -0.128430, -1.682210);
}

}  // namespace
}  // namespace lifelong::io
