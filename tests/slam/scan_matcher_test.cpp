// Correlative multi-resolution scan matcher (Olson 2009) on hand-made scans of a room with
// two boxes, a featureless corridor and an unrelated lattice of posts.
#include "slam/matching/scan_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "tests/slam/synthetic_scans.hpp"

namespace lifelong::slam {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

std::vector<Eigen::Vector2d> Points(const LaserScan& scan) { return ScanToPoints(scan, 0.03); }

// Translation within one fine cell (plus rounding), heading within two angular steps.
void ExpectNear(const Pose2& a, const Pose2& b) {
  EXPECT_NEAR(a.x, b.x, 0.04);
  EXPECT_NEAR(a.y, b.y, 0.04);
  EXPECT_NEAR(NormalizeAngle(a.theta - b.theta), 0.0, 0.01);
}

TEST(ScanMatcherTest, ScanToPointsKeepsReturnsOnlyAndThins) {
  LaserScan scan;
  scan.range_max_m = 10.0;
  scan.angle_increment_rad = 0.001;  // beams 1 mm apart at 1 m: one voxel of 3 cm
  scan.ranges_m = {1.0f, 1.0f, 10.0f, 0.0f, 1.0f};
  const std::vector<Eigen::Vector2d> pts = ScanToPoints(scan, 0.03);
  ASSERT_EQ(pts.size(), 1u);
  EXPECT_NEAR(pts[0].x(), 1.0, 1e-6);
  EXPECT_EQ(ScanToPoints(scan, 0.0).size(), 3u);
}

TEST(ScanMatcherTest, RecoversKnownOffsetForwardAndInverse) {
  const testing::World room = testing::RoomWorld();
  const Pose2 pose_a(3.0, 2.5, 0.2), pose_b = pose_a * Pose2(0.17, -0.11, 4.0 * kDeg);
  const LaserScan a = testing::SimulateScan(room, pose_a), b = testing::SimulateScan(room, pose_b);
  const MatcherConfig config;
  const MatchResult ab = Match(ReferenceGrid(Points(a), config), Points(b), Pose2(), config);
  const MatchResult ba = Match(ReferenceGrid(Points(b), config), Points(a), Pose2(), config);
  ASSERT_TRUE(ab.ok);
  ASSERT_TRUE(ba.ok);
  EXPECT_GT(ab.score, 0.8);
  ExpectNear(ab.T_ref_cur, Between(pose_a, pose_b));
  ExpectNear(ba.T_ref_cur, Between(pose_b, pose_a));
  ExpectNear(ab.T_ref_cur * ba.T_ref_cur, Pose2());
}

TEST(ScanMatcherTest, RecoversTruePoseFromPerturbedGuessAgainstLocalMap) {
  const testing::World room = testing::RoomWorld();
  const Pose2 p0(1.5, 2.0, 0.0), p1(2.5, 2.3, 0.4), p2(3.5, 2.0, -0.3), truth(4.2, 2.6, 0.1);
  const LaserScan s0 = testing::SimulateScan(room, p0), s1 = testing::SimulateScan(room, p1),
                  s2 = testing::SimulateScan(room, p2);
  MatcherConfig config;
  config.angular_step_rad = 0.5 * kDeg;  // 61 rotations over +-15 deg
  const ReferenceGrid local_map(PointsInReference({{&s0, p0}, {&s1, p1}, {&s2, p2}}, 0.03), config);
  const Pose2 guess = truth * Pose2(0.22, -0.17, -9.0 * kDeg);
  const MatchResult r = Match(local_map, Points(testing::SimulateScan(room, truth)), guess, config);
  ASSERT_TRUE(r.ok);
  ExpectNear(r.T_ref_cur, truth);
  // Branch and bound scores far fewer fine poses than the exhaustive lattice.
  const int W = static_cast<int>(std::ceil(config.linear_window_m / config.resolution_m));
  EXPECT_LT(r.evaluations, 61 * (2 * W + 1) * (2 * W + 1) / 4);
  // A well-constrained match: covariance near its floor, information = its inverse.
  EXPECT_LT(std::sqrt(r.covariance(0, 0)), 0.03);
  EXPECT_LT(std::sqrt(r.covariance(2, 2)), 1.0 * kDeg);
  EXPECT_TRUE((r.covariance * r.information).isIdentity(1e-9));
}

TEST(ScanMatcherTest, CorridorIsUncertainAndAmbiguousAlongItsAxis) {
  const testing::World corridor = testing::CorridorWorld();
  const Pose2 pose_a(0.0, 1.0, 0.0), pose_b(0.4, 1.05, 0.02);
  const LaserScan a = testing::SimulateScan(corridor, pose_a, 181, 180.0 * kDeg, 8.0);
  const LaserScan b = testing::SimulateScan(corridor, pose_b, 181, 180.0 * kDeg, 8.0);
  MatcherConfig config;
  config.linear_window_m = 1.0;
  const ReferenceGrid ref(PointsInReference({{&a, pose_a}}, 0.03), config);
  const MatchResult r = Match(ref, Points(b), pose_b * Pose2(0.1, 0.1, 0.0), config);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.T_ref_cur.y, pose_b.y, 0.04);  // across the axis: well determined
  EXPECT_GT(r.covariance(0, 0), 10.0 * r.covariance(1, 1));
  EXPECT_GT(r.ambiguity, 0.9);
}

TEST(ScanMatcherTest, RoomMatchIsNotAmbiguous) {
  const testing::World room = testing::RoomWorld();
  const Pose2 pose(3.0, 2.5, 0.2);
  const LaserScan scan = testing::SimulateScan(room, pose);
  MatcherConfig config;
  config.linear_window_m = 1.0;
  const MatchResult r = Match(ReferenceGrid(Points(scan), config), Points(scan), Pose2(), config);
  ASSERT_TRUE(r.ok);
  EXPECT_LT(r.ambiguity, 0.8);
}

TEST(ScanMatcherTest, UnrelatedGeometryScoresLow) {
  const testing::World room = testing::RoomWorld(), posts = testing::PostsWorld();
  const Pose2 pose(3.0, 2.5, 0.2);
  MatcherConfig config;
  config.linear_window_m = 1.0;
  const LaserScan ref_scan = testing::SimulateScan(posts, Pose2(3.5, 2.0, 0.0), 361, 360.0 * kDeg);
  const ReferenceGrid ref(Points(ref_scan), config);
  const MatchResult r = Match(ref, Points(testing::SimulateScan(room, pose)), Pose2(), config);
  EXPECT_FALSE(r.ok);
  EXPECT_LT(r.score, 0.3);
}

TEST(ScanMatcherTest, EmptyQueryIsNotOk) {
  const MatcherConfig config;
  const ReferenceGrid ref({{1.0, 0.0}}, config);
  EXPECT_FALSE(Match(ref, {}, Pose2(), config).ok);
}

// Every coarse level must bound the fine table exactly (the branch and bound is only exact
// if it does): Bound(l, x, y) is the max of Likelihood over [x, x + 2^l)^2, cells past the
// table's edges counting 0. Checked cell by cell, edges included, on a random point set.
TEST(ScanMatcherTest, CoarseLevelsAreTheExactMaxOfTheFineTable) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-1.0, 1.5);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 40; ++i) points.emplace_back(coord(rng), coord(rng));
  MatcherConfig config;
  config.resolution_m = 0.05;
  config.sigma_m = 0.04;
  config.coarse_factor = 16;
  const ReferenceGrid grid(points, config);
  grid.PrepareAllBounds();
  ASSERT_EQ(grid.num_levels(), 5);
  for (int level = 1; level < grid.num_levels(); ++level) {
    const int side = 1 << level;
    for (int y = 0; y < grid.height(); ++y) {
      for (int x = 0; x < grid.width(); ++x) {
        float expected = 0.0f;
        for (int j = 0; j < side; ++j) {
          for (int i = 0; i < side; ++i)
            expected = std::max(expected, grid.Likelihood(x + i, y + j));
        }
        ASSERT_EQ(grid.Bound(level, x, y), expected)
            << "level " << level << " at " << x << ", " << y;
      }
    }
  }
}

// Cropping the reference to what the search can reach drops points but changes no lookup, so
// the match is the same to rounding: a corridor mapped far past an 8 m scan's reach, matched
// with a wide heading window (the sweep of the rotated scan matters) and at the lattice's
// far corner (the top-level blocks read past +W).
TEST(ScanMatcherTest, CroppingToTheSearchLeavesTheMatchUnchanged) {
  const testing::World corridor = testing::CorridorWorld();
  std::vector<PosedScan> scans;
  std::vector<LaserScan> storage;
  for (int i = -4; i <= 4; ++i) {
    storage.push_back(
        testing::SimulateScan(corridor, Pose2(3.0 * i, 1.0, 0.0), 361, 360.0 * kDeg, 8.0));
  }
  for (int i = 0; i < 9; ++i)
    scans.push_back({&storage[static_cast<std::size_t>(i)], Pose2(3.0 * (i - 4), 1.0, 0.0)});
  const std::vector<Eigen::Vector2d> reference = PointsInReference(scans, 0.03);
  const LaserScan query =
      testing::SimulateScan(corridor, Pose2(0.5, 1.1, 0.3), 91, 90.0 * kDeg, 8.0);
  for (const Pose2& guess : {Pose2(0.3, 0.95, 0.1), Pose2(0.8, 1.4, 0.6)}) {
    MatcherConfig config;
    config.linear_window_m = 0.4;
    config.angular_window_rad = 0.6;
    config.resolution_m = 0.05;
    std::vector<Eigen::Vector2d> cropped = reference;
    CropToSearch(Points(query), guess, config, &cropped);
    EXPECT_LT(cropped.size(), reference.size() / 2);
    EXPECT_GT(cropped.size(), 0u);
    const MatchResult full = Match(ReferenceGrid(reference, config), Points(query), guess, config);
    const MatchResult crop = Match(ReferenceGrid(cropped, config), Points(query), guess, config);
    EXPECT_EQ(crop.evaluations, full.evaluations);
    EXPECT_EQ(crop.bound_evaluations, full.bound_evaluations);
    EXPECT_NEAR(crop.T_ref_cur.x, full.T_ref_cur.x, 1e-9);
    EXPECT_NEAR(crop.T_ref_cur.y, full.T_ref_cur.y, 1e-9);
    EXPECT_NEAR(crop.T_ref_cur.theta, full.T_ref_cur.theta, 1e-9);
    EXPECT_NEAR(crop.score, full.score, 1e-6);
    EXPECT_NEAR(crop.ambiguity, full.ambiguity, 1e-6);
    EXPECT_TRUE(crop.covariance.isApprox(full.covariance, 1e-5));
  }
  std::vector<Eigen::Vector2d> none = reference;
  CropToSearch({}, Pose2(), MatcherConfig(), &none);
  EXPECT_TRUE(none.empty());
}

// The crop's contract, lookup by lookup: with reference points everywhere, every query point
// at every pose of the search lattice (any heading in the window, any translation a bound
// may read: -W .. W + coarse_factor cells) reads the same likelihood from the cropped table.
void ExpectCropAgreesWhereverTheSearchLooks(const std::vector<Eigen::Vector2d>& query,
                                            const Pose2& guess, double window_rad,
                                            std::mt19937* rng) {
  std::uniform_real_distribution<double> coord(-15.0, 15.0), unit(0.0, 1.0);
  std::vector<Eigen::Vector2d> reference;
  for (int i = 0; i < 60000; ++i) reference.emplace_back(coord(*rng), coord(*rng));
  MatcherConfig config;
  config.resolution_m = 0.05;
  config.linear_window_m = 0.5;
  config.angular_window_rad = window_rad;
  config.angular_step_rad = 0.002;
  std::vector<Eigen::Vector2d> cropped = reference;
  CropToSearch(query, guess, config, &cropped);
  if (window_rad < 1.0) {
    ASSERT_LT(cropped.size(), reference.size() * 3 / 4);
  }
  const ReferenceGrid full(reference, config), crop(cropped, config);
  const int W = static_cast<int>(std::ceil(config.linear_window_m / config.resolution_m));
  for (int trial = 0; trial < 3000; ++trial) {
    const double turn = (2.0 * unit(*rng) - 1.0) * config.angular_window_rad;
    const bool edge = trial % 2 == 0;  // half of the poses on the lattice's box edges
    const auto offset = [&](double u) {
      return (edge ? (u < 0.5 ? -W : W + config.coarse_factor - 1)
                   : -W + u * (2 * W + config.coarse_factor - 1)) *
             config.resolution_m;
    };
    const Eigen::Rotation2Dd R(guess.theta + turn);
    const Eigen::Vector2d t(guess.x + offset(unit(*rng)), guess.y + offset(unit(*rng)));
    for (const Eigen::Vector2d& q : query) {
      const Eigen::Vector2d p = R * q + t;
      const Eigen::Vector2i a = full.CellOf(p), b = crop.CellOf(p);
      ASSERT_NEAR(full.Likelihood(a.x(), a.y()), crop.Likelihood(b.x(), b.y()), 1e-6)
          << "window " << window_rad << ", turn " << turn << " at " << p.transpose();
    }
  }
}

TEST(ScanMatcherTest, CroppedTableAgreesWhereverTheSearchLooks) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector2d> query;
  for (int i = 0; i < 60; ++i) {
    const double a = 0.1 * i, r = 0.5 + 7.5 * unit(rng);
    query.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  query.emplace_back(8.0, 0.0);  // straight ahead: its arc bulges past its two ends
  // A wide heading window (the arcs matter), then a narrow one (the translations do).
  for (const double window_rad : {0.7, 0.004}) {
    ExpectCropAgreesWhereverTheSearchLooks(query, Pose2(1.0, -2.0, 0.4), window_rad, &rng);
  }
  // One point alone, with windows past a quarter and past a half turn: its arc's far side
  // is covered by no other point's.
  for (const double window_rad : {2.0, 3.5}) {
    ExpectCropAgreesWhereverTheSearchLooks({{5.0, 0.0}}, Pose2(1.0, -2.0, 3.14159), window_rad,
                                           &rng);
  }
}

// A table rebuilt in place (its memory reused) must equal one built afresh, whatever it held
// before: a larger table, another coarse factor and resolution, or nothing.
TEST(ScanMatcherTest, RebuildingInPlaceEqualsBuildingAfresh) {
  std::mt19937 rng(11);
  const auto random_points = [&](int n, double lo, double hi) {
    std::uniform_real_distribution<double> coord(lo, hi);
    std::vector<Eigen::Vector2d> points;
    for (int i = 0; i < n; ++i) points.emplace_back(coord(rng), coord(rng));
    return points;
  };
  MatcherConfig wide;
  wide.resolution_m = 0.02;
  wide.coarse_factor = 32;
  MatcherConfig config;
  config.resolution_m = 0.05;
  config.sigma_m = 0.04;
  config.coarse_factor = 8;
  const std::vector<Eigen::Vector2d> small = random_points(30, 0.5, 1.5);
  const ReferenceGrid fresh(small, config);
  ReferenceGrid reused;
  EXPECT_EQ(reused.Likelihood(0, 0), 0.0f);
  reused.Build(random_points(200, -4.0, 4.0), wide);
  reused.Build({}, config);
  EXPECT_EQ(reused.width(), 0);
  reused.Build(small, config);
  reused.PrepareAllBounds();
  fresh.PrepareAllBounds();
  ASSERT_EQ(reused.width(), fresh.width());
  ASSERT_EQ(reused.height(), fresh.height());
  ASSERT_EQ(reused.num_levels(), fresh.num_levels());
  EXPECT_EQ(reused.CellOf(small[0]), fresh.CellOf(small[0]));
  for (int level = 0; level < fresh.num_levels(); ++level) {
    for (int y = -1; y <= fresh.height(); ++y) {
      for (int x = -1; x <= fresh.width(); ++x) {
        ASSERT_EQ(reused.Bound(level, x, y), fresh.Bound(level, x, y)) << level << " " << x;
        ASSERT_EQ(reused.LogLikelihood(x, y), fresh.LogLikelihood(x, y));
      }
    }
  }
}

// ln v of the field, floored (the Olson covariance's log-likelihoods): the floor where v is 0
// and outside the table, ln v where that is above it.
TEST(ReferenceGridTest, LogLikelihoodIsTheFlooredLogOfTheField) {
  MatcherConfig config;
  config.resolution_m = 0.05;
  config.sigma_m = 0.05;
  const ReferenceGrid grid({{0.0, 0.0}, {1.0, 0.3}}, config);
  int above_floor = 0, at_floor = 0;
  for (int y = -2; y <= grid.height() + 1; ++y) {
    for (int x = -2; x <= grid.width() + 1; ++x) {
      const float v = grid.Likelihood(x, y);
      const float expected =
          v > 0.0f ? std::max(std::log(v), ReferenceGrid::kLogFloor) : ReferenceGrid::kLogFloor;
      ASSERT_EQ(grid.LogLikelihood(x, y), expected) << x << " " << y;
      (expected > ReferenceGrid::kLogFloor ? above_floor : at_floor) += 1;
    }
  }
  EXPECT_GT(above_floor, 10);  // the peaks, within ~3 sigma of each point
  EXPECT_GT(at_floor, 100);    // the rest of the table, and past its edges
  const Eigen::Vector2i peak = grid.CellOf({0.0, 0.0});
  EXPECT_GT(grid.LogLikelihood(peak.x(), peak.y()), -0.5f);
}

}  // namespace
}  // namespace lifelong::slam
