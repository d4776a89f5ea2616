// Sub-cell refinement after the correlative lattice search (slam/matching/scan_refiner.hpp).
#include "slam/matching/scan_refiner.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "slam/matching/scan_matcher.hpp"
#include "tests/slam/synthetic_scans.hpp"

namespace lifelong::slam {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

double Distance(const Pose2& a, const Pose2& b) { return std::hypot(a.x - b.x, a.y - b.y); }

// Offsets drawn off the 3 cm lattice: the lattice answer is off by up to half a cell, the
// refined one must be closer on average (measured 1.0 against 1.65 cm: 0.6 of it; the bound
// leaves room for another libm) and never worse than a cell.
TEST(ScanRefiner, MovesLatticeMatchesCloserToTheTruth) {
  const testing::World room = testing::RoomWorld();
  const Pose2 pose_a(3.0, 2.5, 0.2);
  const LaserScan a = testing::SimulateScan(room, pose_a);
  MatcherConfig lattice;
  lattice.refine = false;
  MatcherConfig refined = lattice;
  refined.refine = true;
  const ReferenceGrid ref(ScanToPoints(a, 0.03), lattice);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> shift(-0.12, 0.12), turn(-3.0 * kDeg, 3.0 * kDeg);
  double lattice_sum = 0.0, refined_sum = 0.0;
  constexpr int kTrials = 20;
  for (int t = 0; t < kTrials; ++t) {
    const Pose2 truth(shift(rng), shift(rng), turn(rng));
    const auto pts = ScanToPoints(testing::SimulateScan(room, pose_a * truth), 0.03);
    const MatchResult m = Match(ref, pts, Pose2(), lattice);
    const MatchResult r = Match(ref, pts, Pose2(), refined);
    ASSERT_TRUE(m.ok);
    ASSERT_TRUE(r.ok);
    EXPECT_EQ(r.score, m.score);  // the gate still sees the lattice score
    EXPECT_LE(std::abs(r.T_ref_cur.x - m.T_ref_cur.x), lattice.resolution_m + 1e-12);
    EXPECT_LE(std::abs(r.T_ref_cur.y - m.T_ref_cur.y), lattice.resolution_m + 1e-12);
    EXPECT_LT(Distance(r.T_ref_cur, truth), 0.03);
    lattice_sum += Distance(m.T_ref_cur, truth);
    refined_sum += Distance(r.T_ref_cur, truth);
  }
  EXPECT_LT(refined_sum, 0.75 * lattice_sum)
      << lattice_sum / kTrials << " m vs " << refined_sum / kTrials << " m";
}

TEST(ScanRefiner, NeverLowersTheScoreNorLeavesItsBox) {
  const testing::World room = testing::RoomWorld();
  const LaserScan a = testing::SimulateScan(room, Pose2(3.0, 2.5, 0.2));
  const MatcherConfig config;
  const ReferenceGrid ref(ScanToPoints(a, 0.03), config);
  const auto pts = ScanToPoints(testing::SimulateScan(room, Pose2(3.05, 2.45, 0.21)), 0.03);
  // From far off (0.3 m), a box of 1 cm: the result stays inside and scores no lower.
  const Pose2 start(0.3, -0.3, 0.0);
  const RefinedPose r = RefinePose(ref, pts, start, 0.01, 0.001);
  EXPECT_LE(std::abs(r.T_ref_cur.x - start.x), 0.01 + 1e-12);
  EXPECT_LE(std::abs(r.T_ref_cur.y - start.y), 0.01 + 1e-12);
  EXPECT_LE(std::abs(r.T_ref_cur.theta - start.theta), 0.001 + 1e-12);
  EXPECT_GE(r.score, r.start_score);
  // No points, or none on the table: nothing moves.
  const RefinedPose none = RefinePose(ref, {}, start, 0.03, 0.01);
  EXPECT_EQ(none.iterations, 0);
  EXPECT_EQ(none.T_ref_cur.x, start.x);
  const RefinedPose off = RefinePose(ref, {{500.0, 500.0}}, start, 0.03, 0.01);
  EXPECT_EQ(off.iterations, 0);
}

// The interpolated field lies between the four cells around a point (their centres are
// half a cell away) and its gradient matches central differences.
TEST(ScanRefiner, InterpolationStaysWithinItsCellsAndHasTheRightGradient) {
  const MatcherConfig config;
  const ReferenceGrid ref(std::vector<Eigen::Vector2d>{{0.0, 0.0}, {0.5, 0.2}}, config);
  const double r = ref.resolution_m(), h = 1e-6;
  for (double dx : {-0.013, 0.0, 0.021, 0.052}) {
    for (double dy : {-0.007, 0.011, 0.04}) {
      const Eigen::Vector2d p(0.02 + dx, 0.03 + dy);
      double lo = 1.0, hi = 0.0;
      for (double sx : {-0.5, 0.5}) {
        for (double sy : {-0.5, 0.5}) {
          const Eigen::Vector2i c = ref.CellOf(p + r * Eigen::Vector2d(sx, sy));
          lo = std::min<double>(lo, ref.Likelihood(c.x(), c.y()));
          hi = std::max<double>(hi, ref.Likelihood(c.x(), c.y()));
        }
      }
      Eigen::Vector2d g;
      const double v = ref.Interpolate(p, &g);
      EXPECT_GE(v, lo - 1e-12);
      EXPECT_LE(v, hi + 1e-12);
      const Eigen::Vector2d ex(h, 0.0), ey(0.0, h);
      EXPECT_NEAR(g.x(),
                  (ref.Interpolate(p + ex, nullptr) - ref.Interpolate(p - ex, nullptr)) / (2 * h),
                  1e-4);
      EXPECT_NEAR(g.y(),
                  (ref.Interpolate(p + ey, nullptr) - ref.Interpolate(p - ey, nullptr)) / (2 * h),
                  1e-4);
      EXPECT_GT(hi, 0.0);
    }
  }
}

}  // namespace
}  // namespace lifelong::slam
