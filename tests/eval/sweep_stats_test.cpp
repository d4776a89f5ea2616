// The statistics of a sweep against hand-computed and tabulated values.
#include "eval/sweep/sweep_stats.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace lifelong::eval {
namespace {

TEST(SweepStats, StudentTQuantileMatchesTheTable) {
  // Two-sided 95 % (p = 0.975) from standard t tables.
  const std::pair<double, double> table[] = {
      {1, 12.7062047362}, {2, 4.30265272975},  {3, 3.18244630528},  {4, 2.77644510520},
      {5, 2.57058183661}, {10, 2.22813885196}, {30, 2.04227245630}, {100, 1.98397151852}};
  for (const auto& [dof, t] : table) {
    EXPECT_NEAR(StudentTQuantile(0.975, dof), t, 1e-9) << "dof " << dof;
    EXPECT_NEAR(StudentTQuantile(0.025, dof), -t, 1e-9) << "dof " << dof;
  }
  EXPECT_NEAR(StudentTQuantile(0.975, 1e7), 1.959963985, 1e-6);  // the normal limit
  EXPECT_NEAR(StudentTQuantile(0.5, 3), 0.0, 1e-12);
}

TEST(SweepStats, StudentTCdfOfOneDegreeIsTheCauchyCdf) {
  for (double t : {-5.0, -1.0, 0.0, 0.3, 2.0, 40.0}) {
    EXPECT_NEAR(StudentTCdf(t, 1.0), 0.5 + std::atan(t) / M_PI, 1e-13) << t;
  }
}

TEST(SweepStats, IncompleteBetaOfSimpleCases) {
  // I_x(1, 1) = x; I_x(2, 1) = x^2; I_x(1, 3) = 1 - (1 - x)^3.
  for (double x : {0.0, 0.1, 0.5, 0.9, 1.0}) {
    EXPECT_NEAR(RegularizedIncompleteBeta(1, 1, x), x, 1e-14);
    EXPECT_NEAR(RegularizedIncompleteBeta(2, 1, x), x * x, 1e-14);
    EXPECT_NEAR(RegularizedIncompleteBeta(1, 3, x), 1 - std::pow(1 - x, 3), 1e-14);
  }
}

TEST(SweepStats, MeanStdAndIntervalOfFourValues) {
  // {1, 2, 3, 4}: mean 2.5, s^2 = (2.25 + 0.25 + 0.25 + 2.25) / 3 = 5/3,
  // half width = t(0.975, 3) * s / 2 = 3.18244630528 * 0.64549722437 = 2.0542603
  const SampleStats s = ComputeStats({4, 1, 3, 2});
  EXPECT_EQ(s.n, 4);
  EXPECT_DOUBLE_EQ(*s.mean, 2.5);
  EXPECT_NEAR(*s.std, std::sqrt(5.0 / 3.0), 1e-12);
  const double half = 3.18244630528 * std::sqrt(5.0 / 3.0) / 2.0;
  EXPECT_NEAR(*s.ci95_low, 2.5 - half, 1e-9);
  EXPECT_NEAR(*s.ci95_high, 2.5 + half, 1e-9);
  EXPECT_NEAR(half, 2.0542603, 1e-6);
}

TEST(SweepStats, TwoValuesUseTwelvePointSeven) {
  const SampleStats s = ComputeStats({10, 12});  // mean 11, s = sqrt(2)
  EXPECT_NEAR(*s.ci95_high - *s.mean, 12.7062047362 * std::sqrt(2.0) / std::sqrt(2.0), 1e-8);
}

TEST(SweepStats, OneValueHasNoSpreadAndNoInterval) {
  const SampleStats s = ComputeStats({3.5});
  EXPECT_EQ(s.n, 1);
  EXPECT_DOUBLE_EQ(*s.mean, 3.5);
  EXPECT_FALSE(s.std);
  EXPECT_FALSE(s.ci95_low);
  EXPECT_FALSE(s.ci95_high);
  const SampleStats none = ComputeStats({});
  EXPECT_EQ(none.n, 0);
  EXPECT_FALSE(none.mean);
}

}  // namespace
}  // namespace lifelong::eval
