// Tests for io/carmen_log, io/relations and io/tum on tiny hand-made files whose answers
// are worked out in the comments, plus the counts of the shared datasets (SOURCES.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "io/atomic_file.hpp"
#include "io/carmen_log.hpp"
#include "io/relations.hpp"
#include "io/tum.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::io {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
const std::string kData = std::string(LIFELONG_SOURCE_DIR) + "/tests/data/io/";
const std::string kDatasets = std::string(LIFELONG_SHARED_DIR) + "/datasets/";

std::string TempPath(const std::string& name) { return ::testing::TempDir() + "io_log_" + name; }

std::string WriteText(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path) << text;
  return path;
}

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool Exists(const std::string& path) { return std::ifstream(path).good(); }

void ExpectPose(const Pose2& p, double x, double y, double theta, double tol = 1e-9) {
  EXPECT_NEAR(p.x, x, tol);
  EXPECT_NEAR(p.y, y, tol);
  EXPECT_NEAR(NormalizeAngle(p.theta - theta), 0.0, tol);
}

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

TEST(Relations, SubtractsOffsetAndKeepsPlanarPart) {
  const auto rel = ReadRelations(kData + "tiny.relations", 1000.0);
  ASSERT_EQ(rel.size(), 2u);
  EXPECT_DOUBLE_EQ(rel[0].t1_s, 0.5);
  EXPECT_DOUBLE_EQ(rel[0].t2_s, 1.5);
  ExpectPose(rel[0].T_1_2, 0.1, -0.2, 0.5);
  EXPECT_DOUBLE_EQ(rel[1].t2_s, 3.0);
  ExpectPose(rel[1].T_1_2, 1.0, 0.0, -0.25);
  try {
    ReadRelations(WriteText("bad.relations", "1 2 0 0 0 0 0 0\n\n1 2 0 x 0 0 0 0\n"), 0.0);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.field(), "y");
  }
  EXPECT_THROW(ReadRelations(WriteText("short.relations", "1 2 0 0 0\n"), 0.0), InputError);
}

TEST(Tum, WritesFixedFormatAndReadsYawBack) {
  const std::string path = TempPath("traj.tum");
  WriteTum(path, {{1000000000.5, Pose2(1.0, 2.0, kPi / 2)}, {2.0, Pose2(-1.5, 0.25, -3.0)}});
  const std::string text = ReadBytes(path);
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "1000000000.500000 1.000000 2.000000 0.000000 0.000000000 0.000000000 0.707106781 "
            "0.707106781");
  const auto poses = ReadTum(path);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_DOUBLE_EQ(poses[0].stamp_s, 1000000000.5);
  ExpectPose(poses[0].T_world_robot, 1.0, 2.0, kPi / 2, 2e-9);
  ExpectPose(poses[1].T_world_robot, -1.5, 0.25, -3.0, 2e-9);
  EXPECT_THROW(ReadTum(WriteText("bad.tum", "# c\n1 2 3 0 0 0 0\n")), InputError);
}

TEST(Relations, ParsesAStreamAndNamesItInErrors) {
  std::istringstream in("# t1 t2 x y z roll pitch yaw\n10.5 11 0.1 -0.2 9 9 9 0.5\r\n");
  const auto rel = ParseRelations(in, "mem.relations", 10.0);
  ASSERT_EQ(rel.size(), 1u);
  EXPECT_DOUBLE_EQ(rel[0].t1_s, 0.5);
  EXPECT_DOUBLE_EQ(rel[0].t2_s, 1.0);
  ExpectPose(rel[0].T_1_2, 0.1, -0.2, 0.5);
  std::istringstream bad("1 2 0 0 0 0 0 0 0\n");
  try {
    ParseRelations(bad, "mem.relations", 0.0);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "mem.relations");
    EXPECT_EQ(e.line(), 1);
  }
}

TEST(Tum, ParsesAStreamAndNamesItInErrors) {
  std::istringstream in("1.5 1 2 3 0 0 0.7071067811865476 0.7071067811865476\n");
  const auto poses = ParseTum(in, "mem.tum");
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_DOUBLE_EQ(poses[0].stamp_s, 1.5);
  ExpectPose(poses[0].T_world_robot, 1.0, 2.0, kPi / 2);
  std::istringstream bad("1 0 0 0 0 0 0 1\n2 0 0 0 nan 0 0 1\n");
  try {
    ParseTum(bad, "mem.tum");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "mem.tum");
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.field(), "qx");
  }
}

// Found by fuzz_tum: squaring components near 1e200 gave inf - inf = NaN yaw.
TEST(Tum, QuaternionOfAnyNormGivesItsYaw) {
  const auto yaw = [](const std::string& q) {
    std::istringstream in("0 0 0 0 " + q + "\n");
    return ParseTum(in, "q.tum").at(0).T_world_robot.theta;
  };
  EXPECT_NEAR(yaw("0 0 1e200 1e200"), kPi / 2, 1e-12);
  EXPECT_NEAR(yaw("1e300 0 -1e300 1e300"), std::atan2(-2.0, 1.0), 1e-12);
  EXPECT_NEAR(yaw("0 0 -3e-5 3e-5"), -kPi / 2, 1e-12);
  for (const char* q : {"0 0 0 0", "0 0 1e-7 0", "0 0 1e-300 1e-300"}) {
    std::istringstream in(std::string("0 0 0 0 ") + q + "\n");
    EXPECT_THROW(ParseTum(in, "q.tum"), InputError) << q;
  }
}

TEST(Tum, AFolderIsAnInputErrorNotAnEmptyTrajectory) {
  EXPECT_THROW(ReadTum(::testing::TempDir()), InputError);
  EXPECT_THROW(ReadRelations(::testing::TempDir(), 0.0), InputError);
}

// --- shared datasets (SOURCES.md counts) -------------------------------------------------

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
