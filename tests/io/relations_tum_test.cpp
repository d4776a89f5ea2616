// Tests for io/relations and io/tum on tiny hand-made files and streams.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "io/relations.hpp"
#include "io/tum.hpp"
#include "sensor/input_error.hpp"
#include "tests/io/io_test_util.hpp"

namespace lifelong::io {
namespace {

using namespace test_util;  // the io test helpers (tests/io/io_test_util.hpp)

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
// Stamps and positions past sensor/input_bounds.hpp are corruption, refused at their field.
TEST(Tum, StampsAndPositionsPastAnyRobotsAreRefusedAtTheirField) {
  const auto field_of = [](const std::string& line, bool tum) {
    std::istringstream in(line);
    try {
      tum ? (void)ParseTum(in, "b") : (void)ParseRelations(in, "b", 0.0);
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(field_of("1e300 0 0 0 0 0 0 1\n", true), "timestamp");
  EXPECT_EQ(field_of("1 0 -2e7 0 0 0 0 1\n", true), "ty");
  EXPECT_EQ(field_of("1764000000 500000 5500000 0 0 0 0 1\n", true), "accepted");
  EXPECT_EQ(field_of("1 1e11 0 0 0 0 0 0\n", false), "t2");
  EXPECT_EQ(field_of("1 2 3e7 0 0 0 0 0\n", false), "x");
}

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

}  // namespace
}  // namespace lifelong::io
