// ScoreAt (slam/matching/scan_matcher.hpp): the score of one pose, and what the loop closer's local
// uniqueness test reads from it: a corridor scores alike along its axis, not across it.
#include <gtest/gtest.h>

#include <vector>

#include "slam/matching/scan_matcher.hpp"

namespace lifelong::slam {
namespace {

// Two parallel walls at y = -1 and y = 1, from x = -6 to 6, a point every 5 cm.
std::vector<Eigen::Vector2d> Corridor(double x0, double x1) {
  std::vector<Eigen::Vector2d> pts;
  for (double x = x0; x <= x1; x += 0.05) {
    pts.emplace_back(x, -1.0);
    pts.emplace_back(x, 1.0);
  }
  return pts;
}

TEST(ScoreAt, ACorridorScoresAlikeAlongItsAxisOnly) {
  MatcherConfig c;
  c.resolution_m = 0.03;
  c.sigma_m = 0.05;
  const ReferenceGrid ref(Corridor(-6.0, 6.0), c);
  const std::vector<Eigen::Vector2d> query = Corridor(-3.0, 3.0);
  const double best = ScoreAt(ref, query, Pose2());
  EXPECT_GT(best, 0.9);
  EXPECT_GT(ScoreAt(ref, query, Pose2(0.25, 0.0, 0.0)), 0.9 * best);  // along: flat
  EXPECT_LT(ScoreAt(ref, query, Pose2(0.0, 0.25, 0.0)), 0.1 * best);  // across: unique
}

TEST(ScoreAt, AWallEndMakesTheAxisObservable) {
  MatcherConfig c;
  c.resolution_m = 0.03;
  c.sigma_m = 0.05;
  std::vector<Eigen::Vector2d> ref_pts = Corridor(-6.0, 6.0);
  for (double y = -1.0; y <= 1.0; y += 0.05) ref_pts.emplace_back(2.0, y);  // an end wall
  const ReferenceGrid ref(ref_pts, c);
  std::vector<Eigen::Vector2d> query = Corridor(-3.0, 2.0);
  for (double y = -1.0; y <= 1.0; y += 0.05) query.emplace_back(2.0, y);
  const double best = ScoreAt(ref, query, Pose2());
  EXPECT_LT(ScoreAt(ref, query, Pose2(0.25, 0.0, 0.0)), 0.9 * best);
  EXPECT_EQ(ScoreAt(ref, {}, Pose2()), 0.0);
}

}  // namespace
}  // namespace lifelong::slam
