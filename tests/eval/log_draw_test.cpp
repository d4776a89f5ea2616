// A draw of a recorded log (replay --seed): the same seed gives the same stream, another seed
// another one; a lost step stays; the noise has the documented spread.
#include "eval/experiment/log_draw.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace lifelong::eval {
namespace {

// n steps of 1 m forward, turning 0.1 rad each.
std::vector<Observation> Stream(int n) {
  std::vector<Observation> out(static_cast<std::size_t>(n));
  Pose2 T(2.0, -1.0, 0.5);
  for (int i = 0; i < n; ++i) {
    out[static_cast<std::size_t>(i)].stamp_s = i;
    out[static_cast<std::size_t>(i)].T_odom_robot = T;
    out[static_cast<std::size_t>(i)].scan.ranges_m = {static_cast<float>(i)};
    T = T * Pose2(1.0, 0.0, 0.1);
  }
  return out;
}

bool Same(const Pose2& a, const Pose2& b, double tol) {
  return std::abs(a.x - b.x) <= tol && std::abs(a.y - b.y) <= tol &&
         std::abs(NormalizeAngle(a.theta - b.theta)) <= tol;
}

TEST(LogDraw, TheSameSeedGivesTheSameStreamAndAnotherSeedAnother) {
  std::vector<Observation> a = Stream(50), b = Stream(50), c = Stream(50);
  DrawOdometry(7, {}, &a);
  DrawOdometry(7, {}, &b);
  DrawOdometry(8, {}, &c);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(Same(a[i].T_odom_robot, b[i].T_odom_robot, 0.0)) << i;
    EXPECT_EQ(a[i].scan.ranges_m, Stream(50)[i].scan.ranges_m);  // scans untouched
    EXPECT_EQ(a[i].stamp_s, static_cast<double>(i));
  }
  EXPECT_TRUE(Same(a.front().T_odom_robot, Stream(1).front().T_odom_robot, 0.0));
  EXPECT_FALSE(Same(a.back().T_odom_robot, c.back().T_odom_robot, 1e-3));
}

TEST(LogDraw, WithoutNoiseTheStreamIsTheLogsAndALostStepStaysAsRecorded) {
  std::vector<Observation> quiet = Stream(30);
  DrawOdometry(1, {0.0, 0.0, 0.0}, &quiet);
  for (std::size_t i = 0; i < quiet.size(); ++i) {
    EXPECT_TRUE(Same(quiet[i].T_odom_robot, Stream(30)[i].T_odom_robot, 1e-9)) << i;
  }
  std::vector<Observation> drawn = Stream(30);
  drawn[10].odometry_lost = true;
  drawn[10].T_odom_robot = drawn[9].T_odom_robot;  // no odometry over the step
  DrawOdometry(1, {}, &drawn);
  EXPECT_TRUE(Same(drawn[10].T_odom_robot, drawn[9].T_odom_robot, 1e-12));
}

TEST(LogDraw, EachStepIsScaledAndTurnedWithTheDocumentedSpread) {
  const int n = 20001;
  std::vector<Observation> s = Stream(n);
  const OdometryJitter jitter;
  DrawOdometry(3, jitter, &s);
  double sum = 0.0, sum2 = 0.0, turn2 = 0.0;
  for (int i = 1; i < n; ++i) {
    const Pose2 step = Between(s[static_cast<std::size_t>(i) - 1].T_odom_robot,
                               s[static_cast<std::size_t>(i)].T_odom_robot);
    const double scale = Norm(step) - 1.0;  // the recorded step is 1 m
    sum += scale;
    sum2 += scale * scale;
    const double turn = step.theta - 0.1;  // e_t * 0.1 + e_h
    turn2 += turn * turn;
  }
  const double m = n - 1.0;
  EXPECT_NEAR(sum / m, 0.0, 4.0 * jitter.scale_sigma / std::sqrt(m));
  EXPECT_NEAR(std::sqrt(sum2 / m), jitter.scale_sigma, 0.05 * jitter.scale_sigma);
  const double turn_sigma = std::hypot(0.1 * jitter.turn_sigma, jitter.heading_sigma_rad);
  EXPECT_NEAR(std::sqrt(turn2 / m), turn_sigma, 0.05 * turn_sigma);
}

}  // namespace
}  // namespace lifelong::eval
