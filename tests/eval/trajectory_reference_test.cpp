// Scoring against a reference trajectory (eval/metrics/trajectory_reference.hpp) and reading one
// (io::ReadTrajectory).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "eval/metrics/metrics.hpp"
#include "eval/metrics/trajectory_reference.hpp"
#include "io/tum.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

std::vector<StampedPose> Line(int n, double step_m, double dt_s) {
  std::vector<StampedPose> poses;
  for (int k = 0; k < n; ++k) poses.push_back({k * dt_s, Pose2(k * step_m, 0.0, 0.0)});
  return poses;
}

TEST(PairWithReference, InterpolatesBetweenReferencePosesAndDropsGaps) {
  const std::vector<StampedPose> reference = {
      {0.0, Pose2(0, 0, 0)}, {1.0, Pose2(1, 0, 0.2)}, {5.0, Pose2(9, 0, 0.2)}};
  const std::vector<StampedPose> estimate = {
      {0.25, Pose2(0, 0, 0)}, {1.0005, Pose2(0, 0, 0)}, {3.0, Pose2(0, 0, 0)}};
  const ReferencePairs p = PairWithReference(estimate, reference, 1.5, 1e-3);
  ASSERT_EQ(p.reference.size(), 2u);
  EXPECT_NEAR(p.reference[0].x, 0.25, 1e-12);
  EXPECT_NEAR(p.reference[0].theta, 0.05, 1e-12);
  EXPECT_NEAR(p.reference[1].x, 1.0, 1e-12);  // within tolerance: the pose itself
  EXPECT_EQ(p.unmatched, 1u);                 // 3 s lies in a 4 s gap
}

TEST(PairWithReference, HeadingInterpolatesOnTheShortArc) {
  const std::vector<StampedPose> reference = {{0.0, Pose2(0, 0, 3.0)}, {1.0, Pose2(0, 0, -3.0)}};
  const ReferencePairs p = PairWithReference({{0.5, Pose2()}}, reference, 2.0, 1e-3);
  ASSERT_EQ(p.reference.size(), 1u);
  EXPECT_NEAR(std::abs(p.reference[0].theta), M_PI, 1e-9);  // through pi, not through 0
}

TEST(ComputeRpeAtDistance, AnExactEstimateHasNoErrorAndPairsAreOneMetreApart) {
  const std::vector<StampedPose> ref = Line(21, 0.25, 0.1);  // 5 m in 0.25 m steps
  std::vector<Pose2> r;
  for (const auto& p : ref) r.push_back(p.T_world_robot);
  const DistanceRpe exact = ComputeRpeAtDistance(r, r, 1.0);
  EXPECT_EQ(exact.count, 17u);  // i = 0..16, j = i + 4
  EXPECT_DOUBLE_EQ(exact.trans_rmse_m, 0.0);
  // An estimate that stretches every step by 10 %: 0.1 m over each metre.
  std::vector<Pose2> stretched;
  for (const Pose2& p : r) stretched.push_back(Pose2(1.1 * p.x, p.y, p.theta));
  const DistanceRpe s = ComputeRpeAtDistance(stretched, r, 1.0);
  EXPECT_NEAR(s.trans_rmse_m, 0.1, 1e-9);
  EXPECT_EQ(ComputeRpeAtDistance(r, r, 10.0).count, 0u);  // shorter than 10 m
}

// A robot at constant speed covers 1 m in exactly 20 steps of 0.05 m. Moving each pose by
// the rounding of a 6-decimal trajectory file must not move a pair's partner by a step:
// `score` read RPE 2 % off `run`'s own on corridor_3 when it did.
TEST(ComputeRpeAtDistance, TheRoundingOfAFileDoesNotMoveAPairsPartner) {
  std::vector<Pose2> exact, rounded, estimate;
  for (int k = 0; k < 100; ++k) {
    exact.push_back(Pose2(0.05 * k, 0.0, 0.0));
    rounded.push_back(Pose2(0.05 * k + (k % 2 == 0 ? 4e-7 : -4e-7), 0.0, 0.0));
    estimate.push_back(Pose2(0.05 * k, 0.001 * k * k * 0.01, 0.002 * k));
  }
  const DistanceRpe a = ComputeRpeAtDistance(estimate, exact, 1.0);
  const DistanceRpe b = ComputeRpeAtDistance(estimate, rounded, 1.0);
  EXPECT_EQ(a.count, 80u);  // i = 0..79, j = i + 20
  EXPECT_EQ(b.count, a.count);
  EXPECT_NEAR(b.trans_rmse_m, a.trans_rmse_m, 1e-5);
  EXPECT_NEAR(b.rot_rmse_deg, a.rot_rmse_deg, 1e-9);
}

TEST(ComputeRpeAtDistance, ARigidMotionOfTheWholeEstimateCostsNothingButAtEndsAte) {
  std::vector<Pose2> r, moved;
  for (int k = 0; k < 40; ++k) r.push_back(Pose2(0.2 * k, 0.05 * k * k * 0.01, 0.01 * k));
  const Pose2 T(3.0, -2.0, 0.7);
  for (const Pose2& p : r) moved.push_back(T * p);
  EXPECT_NEAR(ComputeRpeAtDistance(moved, r, 1.0).trans_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(ComputeAte(moved, r).rmse_m, 0.0, 1e-9);
}

std::string Write(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::path(::testing::TempDir()) / name;
  std::ofstream(p) << text;
  return p.string();
}

TEST(ReadTrajectory, ReadsTumAndPlainTriplesAndNamesBadLines) {
  const auto tum = io::ReadTrajectory(
      Write("ref.tum", "# comment\n1.0 2 3 0 0 0 0.7071067811865476 0.7071067811865476\n"));
  ASSERT_EQ(tum.size(), 1u);
  EXPECT_NEAR(tum[0].T_world_robot.theta, M_PI / 2, 1e-12);
  const auto plain = io::ReadTrajectory(Write("ref.txt", "\n0 1 2 0.5\n0.2 1.5 2 0.6\n"));
  ASSERT_EQ(plain.size(), 2u);
  EXPECT_DOUBLE_EQ(plain[1].T_world_robot.x, 1.5);
  const std::string five = Write("five.txt", "0 1 2 3 4\n");
  try {
    io::ReadTrajectory(five);
    FAIL() << "a line of 5 fields was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the first line has 5"), std::string::npos) << e.what();
  }
  EXPECT_THROW(io::ReadTrajectory(Write("back.txt", "1 0 0 0\n0.5 0 0 0\n")), InputError);
  EXPECT_THROW(io::ReadTrajectory(Write("empty.txt", "# nothing\n")), InputError);
  EXPECT_THROW(io::ReadTrajectory(Write("bad.txt", "0 0 0 0\n1 0 x 0\n")), InputError);
}

}  // namespace
}  // namespace lifelong::eval
