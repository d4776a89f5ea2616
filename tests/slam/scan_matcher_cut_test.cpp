// The branch and bound started from min_score (MatcherConfig::cut_below_min_score): the full
// search's result where a pose reaches min_score, nothing (NaN) where none does, and less
// work for it.
#include <cmath>

#include <gtest/gtest.h>

#include "slam/matching/scan_matcher.hpp"
#include "tests/slam/synthetic_scans.hpp"

namespace lifelong::slam {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

std::vector<Eigen::Vector2d> Points(const LaserScan& scan) { return ScanToPoints(scan, 0.03); }

MatcherConfig Cut(MatcherConfig config, double min_score) {
  config.min_score = min_score;
  config.cut_below_min_score = true;
  return config;
}

TEST(ScanMatcherCutTest, AMatchAboveMinScoreIsTheSameAsWithoutTheCut) {
  const testing::World room = testing::RoomWorld();
  const Pose2 pose_a(3.0, 2.5, 0.2), pose_b = pose_a * Pose2(0.17, -0.11, 4.0 * kDeg);
  MatcherConfig config;
  config.linear_window_m = 0.6;
  const ReferenceGrid ref(Points(testing::SimulateScan(room, pose_a)), config);
  const std::vector<Eigen::Vector2d> query = Points(testing::SimulateScan(room, pose_b));
  const MatchResult full = Match(ref, query, Pose2(), config);
  ASSERT_TRUE(full.ok);
  // At 0.5 and at the best's own score (which must still pass: the search starts just
  // below min_score).
  for (const double min_score : {0.5, full.score}) {
    const MatchResult cut = Match(ref, query, Pose2(), Cut(config, min_score));
    ASSERT_TRUE(cut.ok) << min_score;
    EXPECT_EQ(cut.score, full.score);
    EXPECT_EQ(cut.T_ref_cur.x, full.T_ref_cur.x);
    EXPECT_EQ(cut.T_ref_cur.y, full.T_ref_cur.y);
    EXPECT_EQ(cut.T_ref_cur.theta, full.T_ref_cur.theta);
    EXPECT_EQ(cut.ambiguity, full.ambiguity);
    // The poses scored are the full search's, so the covariance is too.
    EXPECT_EQ(cut.evaluations, full.evaluations);
    EXPECT_EQ(cut.covariance, full.covariance);
  }
}

TEST(ScanMatcherCutTest, NoPoseAboveMinScoreGivesNaNAtAFractionOfTheWork) {
  const testing::World room = testing::RoomWorld(), posts = testing::PostsWorld();
  MatcherConfig config;
  config.linear_window_m = 1.0;
  const LaserScan ref_scan = testing::SimulateScan(posts, Pose2(3.5, 2.0, 0.0), 361, 360.0 * kDeg);
  const ReferenceGrid ref(Points(ref_scan), config);
  const std::vector<Eigen::Vector2d> query =
      Points(testing::SimulateScan(room, Pose2(3.0, 2.5, 0.2)));
  const MatchResult full = Match(ref, query, Pose2(), config);
  ASSERT_LT(full.score, 0.5);
  const MatchResult cut = Match(ref, query, Pose2(), Cut(config, 0.5));
  EXPECT_FALSE(cut.ok);
  EXPECT_TRUE(std::isnan(cut.score));
  EXPECT_TRUE(std::isnan(cut.ambiguity));
  EXPECT_LT(cut.bound_evaluations, full.bound_evaluations / 2);
  EXPECT_LT(cut.evaluations, full.evaluations);
  // Just above the best: still nothing.
  EXPECT_FALSE(Match(ref, query, Pose2(), Cut(config, std::nextafter(full.score, 1.0))).ok);
}

}  // namespace
}  // namespace lifelong::slam
