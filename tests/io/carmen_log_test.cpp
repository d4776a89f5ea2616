// Tests for io/carmen_log (reader and writer) on tiny hand-made files whose answers are
// worked out in the comments.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "io/atomic_file.hpp"
#include "io/carmen_log.hpp"
#include "sensor/input_error.hpp"
#include "tests/io/io_test_util.hpp"

namespace lifelong::io {
namespace {

using namespace test_util;  // the io test helpers (tests/io/io_test_util.hpp)

/// Expects ReadCarmenLog to throw an InputError on `line` naming `field`.
void ExpectLogError(const std::string& text, int line, const std::string& field) {
  const std::string path = WriteText("bad.clf", text);
  try {
    ReadCarmenLog(path);
    ADD_FAILURE() << "no InputError for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
  }
}

TEST(CarmenRead, TinyLogMessagesConventionsAndCounts) {
  const CarmenLog log = ReadCarmenLog(kData + "tiny.clf");
  ASSERT_EQ(log.observations.size(), 3u);
  ASSERT_EQ(log.odometry.size(), 2u);
  ASSERT_EQ(log.params.size(), 2u);
  EXPECT_EQ(log.params[0].name, "robot_frontlaser_offset");
  EXPECT_EQ(log.params[0].value, "0.1");
  EXPECT_EQ(log.params[1].value, "1 0.0");  // a value with a space
  EXPECT_EQ(log.comment_lines, 1);
  EXPECT_EQ(log.skipped.at("SYNC"), 1);
  EXPECT_EQ(log.skipped.at("RLASER"), 1);
  EXPECT_EQ(log.skipped.count("TRUEPOS"), 0u);  // attached to the ROBOTLASER1 before it
  EXPECT_FALSE(log.odometry_recovered);
  EXPECT_EQ(log.backward_scan_stamps, 1);  // 9.9 after 10.0
  EXPECT_EQ(log.backward_odom_stamps, 1);  // 9.5 after 10.0

  // FLASER, 4 beams: 180/4 = 45 deg steps from -90 deg; range max = largest FLASER reading.
  const Observation& a = log.observations[0];
  EXPECT_DOUBLE_EQ(a.stamp_s, 10.0);
  EXPECT_DOUBLE_EQ(a.scan.stamp_s, 10.0);
  EXPECT_NEAR(a.scan.angle_min_rad, -90 * kDeg, 1e-12);
  EXPECT_NEAR(a.scan.angle_increment_rad, 45 * kDeg, 1e-12);
  EXPECT_NEAR(a.scan.range_max_m, 81.83, 1e-5);
  EXPECT_FALSE(a.scan.IsReturn(2));
  EXPECT_TRUE(a.scan.IsReturn(1));
  ExpectPose(a.T_odom_robot, 0.5, 0.25, 0.1);
  EXPECT_FALSE(a.T_world_robot_true.has_value());
  // FLASER, 5 beams (odd): 180/(5-1) = 45 deg; the odometry triple, not the first, is used.
  const Observation& b = log.observations[1];
  EXPECT_NEAR(b.scan.angle_increment_rad, 45 * kDeg, 1e-12);
  ExpectPose(b.T_odom_robot, 0.6, 0.25, 0.2);
  // ROBOTLASER1: laser (1.1, 2, 0.5) on robot (1, 2, 0) => mount (0.1, 0, 0.5).
  const Observation& c = log.observations[2];
  EXPECT_DOUBLE_EQ(c.scan.angle_min_rad, -1.5);
  EXPECT_DOUBLE_EQ(c.scan.angle_increment_rad, 0.75);
  EXPECT_DOUBLE_EQ(c.scan.range_max_m, 30.0);
  ExpectPose(c.scan.T_robot_laser, 0.1, 0.0, 0.5);
  ExpectPose(c.T_odom_robot, 1.0, 2.0, 0.0);
  ASSERT_TRUE(c.T_world_robot_true.has_value());
  ExpectPose(*c.T_world_robot_true, 3.0, 4.0, 0.1);
  ExpectPose(log.odometry[1].T_odom_robot, 0.6, 0.25, 0.1);
  EXPECT_DOUBLE_EQ(log.odometry[1].stamp_s, 9.5);
}

TEST(CarmenRead, FlaserBeamConventionAndRangeMaxOption) {
  std::string n180 = "FLASER 180", n181 = "FLASER 181";
  for (int i = 0; i < 180; ++i) n180 += " 2.5";
  for (int i = 0; i < 181; ++i) n181 += " 2.5";
  const std::string tail = " 0 0 0 0 0 0 1 h 1\n";
  CarmenReadOptions options;
  options.flaser_range_max_m = 50.0;
  const CarmenLog log = ReadCarmenLog(WriteText("beams.clf", n180 + tail + n181 + tail), options);
  ASSERT_EQ(log.observations.size(), 2u);
  const LaserScan& s180 = log.observations[0].scan;
  const LaserScan& s181 = log.observations[1].scan;
  EXPECT_NEAR(s180.Bearing(0), -90 * kDeg, 1e-12);
  EXPECT_NEAR(s180.Bearing(179), 89 * kDeg, 1e-12);  // CARMEN: -90 + i deg
  EXPECT_NEAR(s181.Bearing(180), 90 * kDeg, 1e-12);  // both ends included
  EXPECT_DOUBLE_EQ(s180.range_max_m, 50.0);
  EXPECT_TRUE(s180.IsReturn(0));
}

// corrected.clf: corrected scan poses c0 = (1.1, 0, 0), c1 = (1.2, 1, pi/2).
// Raw: scan 0 = Between(I, (1,0,0)) = (1,0,0); ODOM@3 = (1,0,0)*Between(c0,(2.1,0,0)) = (2,0,0);
// scan 1 = (1,0,0)*Between(c0,(1.1,1,pi/2)) = (1,0,0)*(0,1,pi/2) = (1,1,pi/2);
// ODOM@5 = (1,1,pi/2)*Between(c1,(1.2,2,pi/2)) = (1,1,pi/2)*(1,0,0) = (1,2,pi/2).
TEST(CarmenRead, RecoversRawOdometryFromCorrectedLog) {
  const CarmenLog log = ReadCarmenLog(kData + "corrected.clf");
  EXPECT_TRUE(log.odometry_recovered);
  EXPECT_EQ(log.dropped_odometry, 2);
  EXPECT_EQ(log.skipped.at("NEFF"), 2);
  ASSERT_EQ(log.observations.size(), 2u);
  ExpectPose(log.observations[0].T_odom_robot, 1.0, 0.0, 0.0);
  ExpectPose(log.observations[1].T_odom_robot, 1.0, 1.0, kPi / 2);
  ASSERT_EQ(log.odometry.size(), 5u);
  const double expected[5][4] = {
      {1, 0, 0, 0}, {2, 1, 0, 0}, {3, 2, 0, 0}, {4, 1, 1, kPi / 2}, {5, 1, 2, kPi / 2}};
  for (int i = 0; i < 5; ++i) {
    EXPECT_DOUBLE_EQ(log.odometry[i].stamp_s, expected[i][0]);
    ExpectPose(log.odometry[i].T_odom_robot, expected[i][1], expected[i][2], expected[i][3]);
  }
  EXPECT_EQ(log.backward_odom_stamps, 0);  // the garbage-stamped ODOMs were dropped

  CarmenReadOptions off;
  off.recovery = OdometryRecovery::kOff;
  const CarmenLog raw = ReadCarmenLog(kData + "corrected.clf", off);
  EXPECT_FALSE(raw.odometry_recovered);
  EXPECT_EQ(raw.odometry.size(), 7u);
  ExpectPose(raw.observations[1].T_odom_robot, 1.2, 1.0, kPi / 2);
}

// seattle-corrected: one of its 241 scans has the ODOM before it stamped 0; the pattern
// holds otherwise and the raw odometry is recovered. A log where most scans break it
// (orebro-corrected: scans stamped 0, the ODOM before each repeating the previous scan's
// corrected pose) keeps no raw odometry and is refused, with the counts.
TEST(CarmenRead, AFewOffStampsStillRecoverButABrokenPatternIsRefusedWithItsCounts) {
  std::string text;
  for (int k = 0; k < 3; ++k) {
    const std::string t = std::to_string(k + 1);
    const std::string x = std::to_string(k * 0.5);
    text += "ODOM " + x + " 0 0 0 0 0 " + (k == 1 ? "0" : t) + " h " + t + "\n";
    text += "FLASER 1 1 " + x + " 0 0 " + x + " 0 0 " + t + " h " + t + "\n";
    text += "ODOM " + x + " 0 0 0 0 0 0 h 0\nNEFF 5\n";
  }
  EXPECT_TRUE(ReadCarmenLog(WriteText("one_off.clf", text)).odometry_recovered);
  std::string broken;
  for (int k = 0; k < 3; ++k) {
    broken += "ODOM 9 9 0 0 0 0 " + std::to_string(k + 5) + " h 0\n";
    broken += "FLASER 1 1 0.5 0 0 0.5 0 0 0 h 0\nNEFF 5\n";
  }
  try {
    ReadCarmenLog(WriteText("broken.clf", broken));
    FAIL() << "a corrected log without raw odometry was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("2 of 3 scans lack the pattern"), std::string::npos)
        << e.what();
  }
}

// seattle-corrected, scan 27: no ODOM between the previous scan's repeat and the scan, and
// the ODOMs after it are chained to its corrected pose (here a turn in place by pi/2). The
// step is lost, not a standstill: the scan keeps the previous raw pose, marked lost, and the
// odometry after it is chained on from there.
TEST(CarmenRead, AScanWithNoOdometryOfItsOwnHasLostItsStep) {
  const std::string text =
      "ODOM 0 0 0 0 0 0 1 h 1\nFLASER 1 1 0 0 0 0 0 0 1 h 1\nODOM 0 0 0 0 0 0 0 h 0\nNEFF 5\n"
      "FLASER 1 1 0 0 1.5707963267948966 0 0 0 2 h 2\n"
      "ODOM 0 0 1.5707963267948966 0 0 0 0 h 0\nNEFF 5\n"
      "ODOM 0 1 1.5707963267948966 0 0 0 3 h 3\n"
      "FLASER 1 1 0 1 1.5707963267948966 0 0 0 3 h 3\n";
  const CarmenLog log = ReadCarmenLog(WriteText("lost_step.clf", text));
  ASSERT_TRUE(log.odometry_recovered);
  ASSERT_EQ(log.observations.size(), 3u);
  EXPECT_FALSE(log.observations[0].odometry_lost);
  EXPECT_TRUE(log.observations[1].odometry_lost);
  EXPECT_FALSE(log.observations[2].odometry_lost);
  EXPECT_EQ(log.lost_odometry_scans, 1);
  EXPECT_EQ(log.first_lost_odometry_line, 5);
  ExpectPose(log.observations[1].T_odom_robot, 0.0, 0.0, 0.0);
  ExpectPose(log.observations[2].T_odom_robot, 1.0, 0.0, 0.0);  // 1 m ahead of the lost pose
}

TEST(CarmenRead, ForcedRecoveryWithoutPatternThrows) {
  CarmenReadOptions on;
  on.recovery = OdometryRecovery::kOn;
  const std::string path = WriteText("nopattern.clf", "FLASER 1 1 0 0 0 0 0 0 1 h 1\n");
  EXPECT_THROW(ReadCarmenLog(path, on), InputError);
  // NEFF without the pattern: refuse to guess.
  EXPECT_THROW(ReadCarmenLog(WriteText("neff.clf", "FLASER 1 1 0 0 0 0 0 0 1 h 1\nNEFF 3\n")),
               InputError);
}

TEST(CarmenRead, CorruptLinesThrowWithLineAndField) {
  const std::string odom = "ODOM 0 0 0 0 0 0 1 h 1\n";
  ExpectLogError(odom + "ODOM 1 2\n", 2, "theta");                               // too few fields
  ExpectLogError(odom + "ODOM 1 abc 0 0 0 0 1 h 1\n", 2, "y");                   // not a number
  ExpectLogError("# c\nFLASER 5 1 1 1 0 0 0 0 0 0 1 h 1\n", 2, "num_readings");  // short
  ExpectLogError("FLASER 2 1 nan 0 0 0 0 0 0 1 h 1\n", 1, "range_readings");     // NaN
  ExpectLogError("FLASER 2 1 1 1 0 0 0 0 0 0 1 h 1\n", 1, "num_readings");  // one beam too many
  ExpectLogError("FLASER -2 0 0 0 0 0 0 1 h 1\n", 1, "num_readings");
  ExpectLogError("ROBOTLASER1 0 -1.5 3.0 0.75 30.0 0.01 0 5 1 2 3\n", 1, "range_readings");
  ExpectLogError("ODOM 0 0 0 0 0 0 1 h 1 7\n", 1, "ODOM");  // an extra field
  ExpectLogError("PARAM onlyname\n", 1, "param_value");
  try {
    ReadCarmenLog(TempPath("does_not_exist.clf"));
    ADD_FAILURE() << "missing file accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 0);
  }
}

// Values no robot log holds are errors on their line, not data: negative ranges, fields of
// view and maximum ranges that are not positive, positions past 1e7 m and stamps past 1e10 s
// (they overflowed the map's cell indices and the outputs' columns).
TEST(CarmenRead, ValuesNoRobotLogHoldsThrowWithLineAndField) {
  const std::string odom = "ODOM 0 0 0 0 0 0 1 h 1\n";
  ExpectLogError(odom + "FLASER 2 1 -3.5 0 0 0 0 0 0 1 h 1\n", 2, "range_readings");
  const std::string rl_tail = " 0 0 0 0 0 0 0 0 0 0 0 1 h 1\n";
  //            ROBOTLASER1 type start fov res max_range acc mode n r r n_rem
  ExpectLogError("ROBOTLASER1 0 -1.5 0 0.75 30.0 0.01 0 2 1 1 0" + rl_tail, 1, "fov");
  ExpectLogError("ROBOTLASER1 0 -1.5 -3 0.75 30.0 0.01 0 2 1 1 0" + rl_tail, 1, "fov");
  ExpectLogError("ROBOTLASER1 0 -1.5 3.0 0.75 -5 0.01 0 2 1 1 0" + rl_tail, 1, "max_range");
  ExpectLogError("ROBOTLASER1 0 -1.5 3.0 -0.1 30 0.01 0 2 1 1 0" + rl_tail, 1, "angular_res");
  ExpectLogError("ROBOTLASER1 0 -1.5 3.0 3.0 30 0.01 0 4 1 1 1 1 0" + rl_tail, 1,
                 "angular_res");  // 4 beams 3 rad apart: 9 rad
  ExpectLogError("ROBOTLASER1 0 -1.5 3.0 0.75 30 0.01 0 2 1 -1 0" + rl_tail, 1, "range_readings");
  ExpectLogError("ODOM 1e308 0 0 0 0 0 1 h 1\n", 1, "x");
  ExpectLogError(odom + "FLASER 1 1 0 0 0 0 -2e7 0 1 h 1\n", 2, "odom_y");
  ExpectLogError(odom + "FLASER 1 1 0 0 0 0 0 0 1e300 h 1\n", 2, "ipc_timestamp");
  ExpectLogError(odom + "FLASER 1 1 0 0 0 0 0 0 1 h -2e10\n", 2, "logger_timestamp");
  // Within the bounds: a Unix stamp, a UTM northing, 0 (no return), a 360 degree field of view.
  const std::string path = WriteText("edge.clf",
                                     "FLASER 2 0 5 0 0 0 500000 5500000 0 1764000000 h 1\n"
                                     "ROBOTLASER1 0 -3.14159 6.2831853 0 30 0.01 0 2 1 1 0" +
                                         rl_tail);
  const CarmenLog log = ReadCarmenLog(path);
  ASSERT_EQ(log.observations.size(), 2u);
  EXPECT_EQ(log.observations[0].T_odom_robot.y, 5500000.0);
  EXPECT_NEAR(log.observations[1].scan.angle_increment_rad, 6.2831853, 1e-9);  // fov / (n - 1)
}

std::vector<Observation> SampleScans() {
  std::vector<Observation> scans(2);
  scans[0].stamp_s = scans[0].scan.stamp_s = 1000000000.25;
  scans[0].T_odom_robot = Pose2(12.3456789, -4.5, 3.0);
  scans[0].scan.angle_min_rad = -2.0943951;
  scans[0].scan.angle_increment_rad = 0.0174532925;
  scans[0].scan.range_max_m = 5.6;
  scans[0].scan.T_robot_laser = Pose2(0.2, -0.05, 0.1);
  scans[0].scan.ranges_m = {0.1234f, 5.6f, 3.14159f};
  scans[0].T_world_robot_true = Pose2(1.0, 2.0, -3.1);
  scans[1] = scans[0];
  scans[1].stamp_s = scans[1].scan.stamp_s = 1000000000.5;
  scans[1].T_world_robot_true.reset();
  return scans;
}

void WriteSample(const std::string& path) {
  CarmenWriter writer(path);
  writer.WriteParam("robot_frontlaser_offset", "0.2");
  writer.WriteOdometry({999999999.75, Pose2(1.0, 2.0, 0.5)});
  for (const Observation& o : SampleScans()) writer.WriteScan(o);
  writer.Close();
}

TEST(CarmenWrite, RoundTripWithinPrintedPrecision) {
  for (const std::string name : {"rt.clf", "rt.clf.gz"}) {
    const std::string path = TempPath(name);
    WriteSample(path);
    EXPECT_FALSE(Exists(TempPathFor(path)));
    const CarmenLog log = ReadCarmenLog(path);
    const std::vector<Observation> in = SampleScans();
    ASSERT_EQ(log.observations.size(), in.size());
    ASSERT_EQ(log.odometry.size(), 1u);
    ASSERT_EQ(log.params.size(), 1u);
    EXPECT_EQ(log.params[0].value, "0.2");
    EXPECT_NEAR(log.odometry[0].stamp_s, 999999999.75, 1e-6);
    ExpectPose(log.odometry[0].T_odom_robot, 1.0, 2.0, 0.5, 1e-6);
    EXPECT_TRUE(log.skipped.empty());
    EXPECT_FALSE(log.odometry_recovered);
    for (std::size_t i = 0; i < in.size(); ++i) {
      const Observation& got = log.observations[i];
      EXPECT_NEAR(got.stamp_s, in[i].stamp_s, 1e-6);
      ExpectPose(got.T_odom_robot, in[i].T_odom_robot.x, in[i].T_odom_robot.y,
                 in[i].T_odom_robot.theta, 1e-6);
      const Pose2& m = in[i].scan.T_robot_laser;
      ExpectPose(got.scan.T_robot_laser, m.x, m.y, m.theta, 2e-5);  // via two 1e-6 poses
      EXPECT_NEAR(got.scan.angle_min_rad, in[i].scan.angle_min_rad, 1e-9);
      EXPECT_NEAR(got.scan.angle_increment_rad, in[i].scan.angle_increment_rad, 1e-9);
      EXPECT_NEAR(got.scan.range_max_m, in[i].scan.range_max_m, 1e-4);
      ASSERT_EQ(got.scan.ranges_m.size(), in[i].scan.ranges_m.size());
      for (std::size_t k = 0; k < got.scan.ranges_m.size(); ++k) {
        EXPECT_NEAR(got.scan.ranges_m[k], in[i].scan.ranges_m[k], 5e-5);
      }
      ASSERT_EQ(got.T_world_robot_true.has_value(), in[i].T_world_robot_true.has_value());
    }
    ExpectPose(*log.observations[0].T_world_robot_true, 1.0, 2.0, -3.1, 1e-6);
  }
}

TEST(CarmenWrite, SameStreamGivesByteIdenticalFiles) {
  WriteSample(TempPath("same_a.clf"));
  WriteSample(TempPath("same_b.clf"));
  const std::string a = ReadBytes(TempPath("same_a.clf"));
  EXPECT_GT(a.size(), 100u);
  EXPECT_EQ(a, ReadBytes(TempPath("same_b.clf")));
  EXPECT_NE(a.find("ODOM 1.000000 2.000000 0.500000 0 0 0 999999999.750000 lifelong"),
            std::string::npos);
}

TEST(CarmenWrite, UnclosedWriterLeavesNoFileAndBadPathThrows) {
  const std::string path = TempPath("unclosed.clf");
  std::remove(path.c_str());
  {
    CarmenWriter writer(path);
    writer.WriteOdometry({1.0, Pose2()});
    EXPECT_TRUE(Exists(TempPathFor(path)));
  }
  EXPECT_FALSE(Exists(path));
  EXPECT_FALSE(Exists(TempPathFor(path)));
  EXPECT_THROW(CarmenWriter(TempPath("no_such_dir/x.clf")), InputError);
}

TEST(CarmenRead, TruncatedGzipThrows) {
  const std::string path = TempPath("trunc.clf.gz");
  {
    CarmenWriter writer(path);
    for (const Observation& o : SampleScans()) writer.WriteScan(o);
    writer.Close();
  }
  const std::string bytes = ReadBytes(path);
  std::ofstream(path, std::ios::binary) << bytes.substr(0, bytes.size() - 12);  // no trailer
  EXPECT_THROW(ReadCarmenLog(path), InputError);
}

}  // namespace
}  // namespace lifelong::io
