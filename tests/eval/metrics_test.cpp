// Trajectory metrics on tiny trajectories whose answers are worked out by hand.
#include "eval/metrics/metrics.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace lifelong::eval {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<Pose2> Square() { return {{0, 0, 0}, {2, 0, 0.5}, {2, 1, 1.0}, {0, 1, 2.0}}; }

TEST(AteTest, RotatedAndShiftedCopyHasZeroErrorAndRecoversTheTransform) {
  const Pose2 T_est_truth(3.0, -2.0, kPi / 2);
  std::vector<Pose2> est;
  for (const Pose2& p : Square()) est.push_back(T_est_truth * p);
  const AteResult r = ComputeAte(est, Square());
  EXPECT_EQ(r.count, 4u);
  EXPECT_NEAR(r.rmse_m, 0.0, 1e-12);
  EXPECT_NEAR(r.rot_rmse_deg, 0.0, 1e-9);
  const Pose2 back = r.T_truth_est * T_est_truth;  // must be identity
  EXPECT_NEAR(back.x, 0.0, 1e-12);
  EXPECT_NEAR(back.y, 0.0, 1e-12);
  EXPECT_NEAR(back.theta, 0.0, 1e-12);
}

// Poses on the x axis at x = 0..3; poses 0 and 3 are off by +0.1 m in y. By symmetry the
// best alignment is a 0.05 m shift in y and no rotation, leaving |e| = 0.05 everywhere.
TEST(AteTest, OffsetOnHalfThePosesGivesHandComputedRmse) {
  const std::vector<Pose2> truth = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  const std::vector<Pose2> est = {{0, 0.1, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0.1, 0}};
  const AteResult r = ComputeAte(est, truth);
  EXPECT_NEAR(r.rmse_m, 0.05, 1e-12);
  EXPECT_NEAR(r.max_m, 0.05, 1e-12);
  EXPECT_NEAR(r.T_truth_est.y, -0.05, 1e-12);
  EXPECT_NEAR(r.T_truth_est.theta, 0.0, 1e-12);
}

TEST(AteTest, AlignmentIsAMinimumOfTheSquaredError) {
  const std::vector<Pose2> truth = Square();
  const std::vector<Pose2> est = {{0.1, 0.3, 0}, {2.2, -0.1, 0}, {1.7, 1.2, 0}, {0.2, 0.8, 0}};
  const Pose2 T = AlignSE2(est, truth);
  auto sse = [&](const Pose2& A) {
    double s = 0;
    for (std::size_t i = 0; i < est.size(); ++i) {
      const Pose2 p = A * est[i];
      s += std::pow(p.x - truth[i].x, 2) + std::pow(p.y - truth[i].y, 2);
    }
    return s;
  };
  const double best = sse(T);
  for (const Pose2& d :
       {Pose2(1e-3, 0, 0), Pose2(0, -1e-3, 0), Pose2(0, 0, 1e-3), Pose2(0, 0, -1e-3)}) {
    EXPECT_GT(sse(T * d), best);
    EXPECT_GT(sse(d * T), best);
  }
}

TEST(AteTest, SizeMismatchThrows) {
  EXPECT_THROW(ComputeAte({{0, 0, 0}}, {}), std::invalid_argument);
}

TEST(RpeTest, TenPercentLongStepsGiveTenPercentPerMetre) {
  std::vector<Pose2> truth, est;
  for (int i = 0; i < 5; ++i) {
    truth.emplace_back(1.0 * i, 0, 0);
    est.emplace_back(1.1 * i, 0, 0);
  }
  const RpeResult r1 = ComputeRpe(est, truth, 1);
  EXPECT_EQ(r1.count, 4u);
  EXPECT_NEAR(r1.trans_rmse_m, 0.1, 1e-12);
  EXPECT_NEAR(r1.trans_per_m, 0.1, 1e-12);
  EXPECT_NEAR(r1.rot_mean_deg, 0.0, 1e-12);
  const RpeResult r2 = ComputeRpe(est, truth, 2);  // pairs (0,2) (1,3) (2,4): 0.2 m each
  EXPECT_EQ(r2.count, 3u);
  EXPECT_NEAR(r2.trans_mean_m, 0.2, 1e-12);
  EXPECT_NEAR(r2.trans_per_m, 0.1, 1e-12);
}

TEST(RpeTest, HeadingErrorOfOneStepShowsInRotation) {
  const std::vector<Pose2> truth = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const std::vector<Pose2> est = {{0, 0, 0}, {1, 0, 0.1}, {2, 0, 0.1}};
  const RpeResult r = ComputeRpe(est, truth, 1);  // errors 0.1 rad, then 0
  EXPECT_NEAR(r.rot_mean_deg, 0.05 * 180 / kPi, 1e-9);
  EXPECT_NEAR(r.rot_rmse_deg, std::sqrt(0.005) * 180 / kPi, 1e-9);
}

std::vector<StampedPose> Stamped() {
  return {{0.0, {0, 0, 0}}, {1.0, {1, 0, 0}}, {2.0, {2, 0, kPi / 2}}};
}

TEST(RelationsTest, MatchesWithinToleranceNeverInterpolatesAndCountsUnmatched) {
  const std::vector<Relation> rel = {
      {0.0, 1.0, {1.1, 0, 0}},               // error (0.1, 0, 0)
      {0.0005, 2.0, {2, 0, kPi / 2 + 0.1}},  // error (0, 0, 0.1 rad)
      {0.5, 1.0, {0.5, 0, 0}},               // t1 between poses: unmatched, not interpolated
      {1.0, 2.002, {1, 0, 0}},               // t2 off by 2 ms: unmatched
  };
  const RelationsResult r = ComputeRelationsError(Stamped(), rel);
  EXPECT_EQ(r.count, 2u);
  EXPECT_EQ(r.unmatched, 2u);
  EXPECT_NEAR(r.trans_mean_m, 0.05, 1e-12);
  EXPECT_NEAR(r.trans_std_m, 0.05, 1e-12);
  EXPECT_NEAR(r.rot_mean_deg, 0.05 * 180 / kPi, 1e-9);
  EXPECT_NEAR(r.rot_std_deg, 0.05 * 180 / kPi, 1e-9);
}

TEST(RelationsTest, UnsortedEstimateIsLookedUpByStamp) {
  std::vector<StampedPose> est = Stamped();
  std::swap(est[0], est[2]);
  const RelationsResult r = ComputeRelationsError(est, {{0.0, 1.0, {1, 0, 0}}});
  EXPECT_EQ(r.count, 1u);
  EXPECT_NEAR(r.trans_mean_m, 0.0, 1e-12);
}

TEST(MatchByStampTest, PairsNearestWithinToleranceOnly) {
  const std::vector<StampedPose> est = {{0.0004, {5, 0, 0}}, {1.5, {6, 0, 0}}};
  const MatchedPoses m = MatchByStamp(est, Stamped());
  ASSERT_EQ(m.estimate.size(), 1u);
  EXPECT_EQ(m.unmatched, 1u);
  EXPECT_EQ(m.estimate[0].x, 5.0);
  EXPECT_EQ(m.truth[0].x, 0.0);
}

TEST(PercentileTest, InterpolatesBetweenOrderStatistics) {
  EXPECT_DOUBLE_EQ(Percentile({4, 1, 3, 2}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(Percentile({1, 2, 3, 4, 5}, 0.95), 4.8);
  EXPECT_DOUBLE_EQ(Percentile({}, 0.5), 0.0);
}

// Two passes along the x axis, the second 0.2 m to the side: nodes 60..119 revisit
// nodes 0..59 (60 nodes older, 0.2 m away, same heading).
std::vector<Pose2> TwoPasses() {
  std::vector<Pose2> nodes;
  for (int k = 0; k < 120; ++k) nodes.emplace_back(0.5 * (k % 60), k < 60 ? 0.0 : 0.2, 0.0);
  return nodes;
}

TEST(LoopClosureTest, PrecisionAndRecallByHand) {
  const std::vector<Pose2> nodes = TwoPasses();
  auto rel = [&](int i, int j) { return Between(nodes[i], nodes[j]); };
  const std::vector<LoopClosure> closures = {
      {60, 0, rel(60, 0)},                                   // correct
      {70, 10, rel(70, 10) * Pose2(0.5, 0, 0)},              // 0.5 m off: wrong
      {80, 20, rel(80, 20) * Pose2(0.2, 0, 3 * kPi / 180)},  // within 0.3 m, 5 deg
      {90, 85, rel(90, 85)},  // correct, but only 5 nodes older: no recall credit
  };
  const LoopClosureResult r = ComputeLoopClosureStats(closures, nodes);
  EXPECT_EQ(r.accepted, 4);
  EXPECT_EQ(r.correct, 3);
  EXPECT_DOUBLE_EQ(r.precision, 0.75);
  EXPECT_EQ(r.revisit_nodes, 60);
  EXPECT_EQ(r.recalled_nodes, 2);
  EXPECT_DOUBLE_EQ(r.recall, 2.0 / 60.0);
}

TEST(LoopClosureTest, NoRevisitsWhenTheGapIsTooLarge) {
  LoopClosureConfig config;
  config.min_index_gap = 61;
  const LoopClosureResult r = ComputeLoopClosureStats({}, TwoPasses(), config);
  EXPECT_EQ(r.accepted, 0);
  EXPECT_EQ(r.revisit_nodes, 59);  // nodes 61..119 still reach nodes 0..58
  config.revisit_dist_m = 0.1;     // the passes are 0.2 m apart
  EXPECT_EQ(ComputeLoopClosureStats({}, TwoPasses(), config).revisit_nodes, 0);
}

TEST(LoopClosureTest, OutOfRangeNodeThrows) {
  EXPECT_THROW(ComputeLoopClosureStats({{0, 500, Pose2()}}, TwoPasses()), std::invalid_argument);
}

// The curve counts a closure from the observation that accepted it (the timeline's
// cumulative count), not by stamp: a log whose scans share one stamp once counted all its
// closures, wrong ones included, at the first observation.
TEST(LoopCurveTest, ClosuresCountFromTheObservationThatAcceptedThem) {
  std::vector<TimelineRow> timeline(5);
  const int closures_so_far[] = {0, 1, 1, 3, 3};
  for (int n = 0; n < 5; ++n) {
    timeline[static_cast<std::size_t>(n)].obs = n;
    timeline[static_cast<std::size_t>(n)].t_s = 7.0;  // one stamp for every scan
    timeline[static_cast<std::size_t>(n)].loop_closures = closures_so_far[n];
  }
  LoopClosureResult truth;
  truth.correct_each = {true, false, true};
  truth.revisit_each = {false, false, true, true, false};
  truth.recalled_each = {false, false, true, false, false};
  const std::vector<LoopCurvePoint> curve = LoopCurve(timeline, truth);
  ASSERT_EQ(curve.size(), 5u);
  const int accepted[] = {0, 1, 1, 3, 3}, revisits[] = {0, 0, 1, 2, 2};
  for (std::size_t n = 0; n < 5; ++n) {
    EXPECT_EQ(curve[n].obs, static_cast<int>(n));
    EXPECT_EQ(curve[n].accepted, accepted[n]) << n;
    EXPECT_EQ(curve[n].revisits, revisits[n]) << n;
  }
  EXPECT_DOUBLE_EQ(curve[1].precision, 1.0);
  EXPECT_DOUBLE_EQ(curve[3].precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(curve[2].recall, 1.0);
  EXPECT_DOUBLE_EQ(curve[4].recall, 0.5);
}

TEST(LoopCurveTest, StampsAdvanceUnlessTheyRepeatOrGoBack) {
  const auto at = [](std::vector<double> stamps) {
    std::vector<LoopCurvePoint> curve;
    for (double t : stamps) curve.push_back({t, 0.0, 0.0, 0, 0, 0});
    return curve;
  };
  EXPECT_TRUE(StampsAdvance(at({})));
  EXPECT_TRUE(StampsAdvance(at({3.0})));
  EXPECT_TRUE(StampsAdvance(at({1.0, 1.0, 2.0})));
  EXPECT_FALSE(StampsAdvance(at({4.0, 4.0, 4.0})));
  EXPECT_FALSE(StampsAdvance(at({1.0, 3.0, 2.0, 5.0})));
}

}  // namespace
}  // namespace lifelong::eval
