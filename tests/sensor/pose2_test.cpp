#include "sensor/pose2.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace lifelong {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(NormalizeAngle, WrapsIntoHalfOpenInterval) {
  EXPECT_NEAR(NormalizeAngle(0.0), 0.0, 1e-15);
  EXPECT_NEAR(NormalizeAngle(3.0 * kPi / 2.0), -kPi / 2.0, 1e-12);
  EXPECT_NEAR(NormalizeAngle(-3.0 * kPi / 2.0), kPi / 2.0, 1e-12);
  EXPECT_NEAR(NormalizeAngle(kPi), -kPi, 1e-12);
  EXPECT_NEAR(NormalizeAngle(7.0 * 2.0 * kPi + 0.1), 0.1, 1e-9);
}

TEST(Pose2, ComposeByHand) {
  const Pose2 a(1.0, 2.0, kPi / 2.0);
  const Pose2 b(1.0, 0.0, 0.0);
  const Pose2 ab = a * b;  // one metre forward while facing +y
  EXPECT_NEAR(ab.x, 1.0, 1e-12);
  EXPECT_NEAR(ab.y, 3.0, 1e-12);
  EXPECT_NEAR(ab.theta, kPi / 2.0, 1e-12);
}

TEST(Pose2, InverseAndBetween) {
  const Pose2 a(0.3, -1.2, 2.9);
  const Pose2 b(-4.0, 0.5, -2.8);
  const Pose2 id = a * a.Inverse();
  EXPECT_NEAR(id.x, 0.0, 1e-12);
  EXPECT_NEAR(id.y, 0.0, 1e-12);
  EXPECT_NEAR(id.theta, 0.0, 1e-12);
  const Pose2 b_again = a * Between(a, b);
  EXPECT_NEAR(b_again.x, b.x, 1e-12);
  EXPECT_NEAR(b_again.y, b.y, 1e-12);
  EXPECT_NEAR(b_again.theta, b.theta, 1e-12);
}

TEST(Pose2, ApplyMatchesComposition) {
  const Pose2 a(1.0, 1.0, kPi / 2.0);
  double x = 0.0, y = 0.0;
  a.Apply(2.0, 0.0, &x, &y);
  EXPECT_NEAR(x, 1.0, 1e-12);
  EXPECT_NEAR(y, 3.0, 1e-12);
}

}  // namespace
}  // namespace lifelong
