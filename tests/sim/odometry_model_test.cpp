#include "sim/odometry_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace lifelong::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(IntegrateWheels, StraightAndTurnInPlace) {
  const Pose2 p = IntegrateWheels(Pose2(1, 2, kPi / 2), {0.5, 0.5}, 0.33);
  EXPECT_NEAR(p.x, 1.0, 1e-12);
  EXPECT_NEAR(p.y, 2.5, 1e-12);
  // Wheels roll +-b*pi/4 on track b: a quarter turn on the spot.
  const double b = 0.4, arc = b * kPi / 4;
  const Pose2 q = IntegrateWheels(Pose2(), {-arc, arc}, b);
  EXPECT_NEAR(q.x, 0.0, 1e-12);
  EXPECT_NEAR(q.theta, kPi / 2, 1e-12);
}

TEST(WheelOdometry, SystematicScalesGiveHandComputedError) {
  OdometryConfig c;
  c.slip_variance_m2_per_m = 0.0;
  c.left_scale = c.right_scale = 1.02;  // 2 % long on both wheels
  c.track_scale = 1.0;
  WheelOdometry odom(c, 0.33, Pose2());
  std::mt19937_64 rng(1);
  for (int i = 0; i < 100; ++i) odom.Update({0.01, 0.01}, &rng);  // 1 m straight
  EXPECT_NEAR(odom.pose().x, 1.02, 1e-12);
  EXPECT_NEAR(odom.pose().theta, 0.0, 1e-12);

  c.left_scale = c.right_scale = 1.0;
  c.track_scale = 1.1;  // turning in place by pi reads pi / 1.1
  WheelOdometry turn(c, 0.33, Pose2());
  const double arc = 0.33 * kPi / 2;
  turn.Update({-arc, arc}, &rng);
  EXPECT_NEAR(turn.pose().theta, NormalizeAngle(kPi / 1.1), 1e-12);
}

TEST(Gaussian, MomentsOfManySamples) {
  std::mt19937_64 rng(3);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double g = Gaussian(&rng);
    sum += g;
    sum2 += g * g;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);    // 4.5 standard errors
  EXPECT_NEAR(sum2 / n, 1.0, 0.015);  // 4.7 standard errors
}

}  // namespace
}  // namespace lifelong::sim
