// The loop closer on its own, without a Mapper: a chain of nodes that crosses a room and
// comes back, with the return's estimate off by a known amount.
#include "slam/loops/loop_closer.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "synthetic_scans.hpp"

namespace lifelong::slam {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Nodes 0..6 cross the room along y = 2.5 eastwards, 7..12 come back westwards; node 12 stands
// where node 0 stood, turned round. Its estimate is off by `offset`.
struct Chain {
  PoseGraph graph;
  Values values;
  NodeStore nodes;
  std::vector<NodeId> recent;
  std::vector<Pose2> truth;

  explicit Chain(const Pose2& offset) {
    const testing::World room = testing::RoomWorld();
    for (int i = 0; i <= 6; ++i) truth.emplace_back(1.0 + i, 2.5, 0.0);
    for (int i = 1; i <= 6; ++i) truth.emplace_back(7.0 - i, 2.5, kPi);
    for (std::size_t i = 0; i < truth.size(); ++i) {
      const auto id = static_cast<NodeId>(i);
      graph.AddNode(id);
      NodeData data;
      data.scan = testing::SimulateScan(room, truth[i], 361, 2.0 * kPi * 360.0 / 361.0);
      data.points = ScanToPoints(data.scan, 0.05);
      data.scan_index = static_cast<int>(i);
      data.travelled_m = static_cast<double>(i);
      nodes.emplace(id, std::move(data));
      values[id] = truth[i];
      recent.push_back(id);
      if (i == 0) continue;
      PoseEdge edge;
      edge.from = id - 1;
      edge.to = id;
      edge.T_from_to = Between(truth[i - 1], truth[i]);
      edge.information = Eigen::Vector3d(400.0, 400.0, 2500.0).asDiagonal();  // 5 cm, 1.1 deg
      graph.AddEdge(edge);
    }
    const NodeId last = recent.back();
    values[last] = Pose2(truth.back().x + offset.x, truth.back().y + offset.y,
                         truth.back().theta + offset.theta);
  }
  LoopClosingView View() const { return {graph, values, nodes, recent}; }
};

LoopClosingConfig Immediate() {
  LoopClosingConfig lc;
  lc.verify.enabled = false;  // every hypothesis is accepted at once
  lc.matcher.resolution_m = 0.05;
  lc.matcher.sigma_m = 0.08;
  return lc;
}

TEST(LoopCloser, ClosesTheReturnOntoTheStartAndCorrectsItsOffset) {
  const Chain chain(Pose2(0.25, -0.15, 0.04));
  LoopCloser closer(Immediate(), IncrementalConfig{});
  std::vector<LoopHypothesis> accepted;
  const auto attempt = closer.SearchLocal(chain.View(), 12, 0, &accepted);
  ASSERT_TRUE(attempt.has_value());
  EXPECT_EQ(attempt->search, LoopAttempt::Search::kLocal);
  EXPECT_EQ(attempt->current, 12);
  EXPECT_GE(attempt->old, 0);
  EXPECT_LT(attempt->old, 12);
  EXPECT_GE(attempt->measured.score, Immediate().min_score);
  EXPECT_LE(attempt->measured.score, 1.0);
  // Accepted, so its rival (if any) stayed under max_ambiguity of its score.
  EXPECT_GE(attempt->measured.ambiguity, 0.0);
  EXPECT_LE(attempt->measured.ambiguity, Immediate().max_ambiguity);
  EXPECT_FALSE(attempt->refused.has_value());
  EXPECT_TRUE(attempt->proposed);
  EXPECT_GE(attempt->candidates, 1);
  EXPECT_GE(attempt->window_m, Immediate().min_window_m);
  EXPECT_LE(attempt->window_m, Immediate().max_window_m);
  ASSERT_EQ(accepted.size(), 1u);
  ASSERT_EQ(attempt->accepted, 1);
  const LoopHypothesis& h = accepted.front();
  EXPECT_EQ(h.current, 12);
  // Wherever the closure is attached, it measures the true relative pose.
  const Pose2 truth = Between(chain.truth[static_cast<std::size_t>(h.old)], chain.truth[12]);
  EXPECT_NEAR(h.T_old_current.x, truth.x, 0.05);
  EXPECT_NEAR(h.T_old_current.y, truth.y, 0.05);
  EXPECT_NEAR(NormalizeAngle(h.T_old_current.theta - truth.theta), 0.0, 0.02);
  EXPECT_EQ(closer.stats().attempts, 1);
  EXPECT_EQ(closer.stats().proposed, 1);
}

// A search with min_score above any score a match can reach: refused as low_score, the
// attempt still naming the node it was matched against, for loop_attempts.csv.
LoopAttempt RefusedAttempt(bool measure_low_scores) {
  const Chain chain(Pose2(0.1, 0.05, 0.0));
  LoopClosingConfig lc = Immediate();
  lc.min_score = 1.5;
  lc.measure_low_scores = measure_low_scores;
  LoopCloser closer(lc, IncrementalConfig{});
  std::vector<LoopHypothesis> accepted;
  const auto attempt = closer.SearchLocal(chain.View(), 12, 0, &accepted);
  EXPECT_TRUE(accepted.empty());
  EXPECT_TRUE(attempt.has_value());
  return attempt.value_or(LoopAttempt{});
}

TEST(LoopCloser, ARefusedAttemptKeepsItsScoreAndCandidateWhenMeasured) {
  const LoopAttempt attempt = RefusedAttempt(true);
  ASSERT_TRUE(attempt.refused.has_value());
  EXPECT_EQ(*attempt.refused, MatchRefusal::kLowScore);
  EXPECT_FALSE(attempt.proposed);
  EXPECT_GE(attempt.old, 0);
  EXPECT_GT(attempt.measured.score, 0.5);  // the right place, refused only by the threshold
  EXPECT_LT(attempt.measured.score, 1.5);
  EXPECT_FALSE(std::isnan(attempt.measured.ambiguity));
}

TEST(LoopCloser, ARefusedAttemptLeavesItsScoreUnmeasuredByDefault) {
  // The search stops at min_score (MatcherConfig::cut_below_min_score): the same refusal and
  // candidate, no score.
  ASSERT_FALSE(LoopClosingConfig{}.measure_low_scores);
  const LoopAttempt attempt = RefusedAttempt(false);
  ASSERT_TRUE(attempt.refused.has_value());
  EXPECT_EQ(*attempt.refused, MatchRefusal::kLowScore);
  EXPECT_GE(attempt.old, 0);
  EXPECT_TRUE(std::isnan(attempt.measured.score));
}

TEST(LoopCloser, NoCandidateNoAttempt) {
  // Nodes along the graph within min_path_separation_m are no candidates: with the whole
  // chain inside it, there is nothing to search.
  const Chain chain(Pose2(0.0, 0.0, 0.0));
  LoopClosingConfig lc = Immediate();
  lc.min_path_separation_m = 100.0;
  LoopCloser closer(lc, IncrementalConfig{});
  std::vector<LoopHypothesis> accepted;
  EXPECT_FALSE(closer.SearchLocal(chain.View(), 12, 0, &accepted).has_value());
  EXPECT_TRUE(accepted.empty());
  EXPECT_EQ(closer.stats().attempts, 0);
}

TEST(LoopCloser, CandidatesBeyondTheLargestWindowAreSearchedAtEveryNthObservationOnly) {
  // The chain's 12 odometry edges leave the start about 0.3 m uncertain (3 sigma beyond a
  // 0.35 m window) relative to the return.
  const Chain chain(Pose2(0.1, 0.05, 0.0));
  LoopClosingConfig lc = Immediate();
  lc.min_window_m = 0.1;
  lc.max_window_m = 0.35;
  lc.beyond_window_every = 3;
  LoopCloser closer(lc, IncrementalConfig{});
  std::vector<LoopHypothesis> accepted;
  EXPECT_FALSE(closer.SearchLocal(chain.View(), 12, 1, &accepted).has_value());
  EXPECT_FALSE(closer.SearchLocal(chain.View(), 12, 2, &accepted).has_value());
  EXPECT_EQ(closer.stats().beyond_window, 2);
  EXPECT_EQ(closer.stats().attempts, 0);
  const auto wide = closer.SearchLocal(chain.View(), 12, 3, &accepted);
  ASSERT_TRUE(wide.has_value());
  EXPECT_DOUBLE_EQ(wide->window_m, 0.35);  // clamped
  EXPECT_EQ(closer.stats().attempts, 1);

  lc.beyond_window_every = 0;  // never
  LoopCloser never(lc, IncrementalConfig{});
  for (int obs = 0; obs < 4; ++obs) {
    EXPECT_FALSE(never.SearchLocal(chain.View(), 12, obs, &accepted).has_value());
  }
  EXPECT_EQ(never.stats().beyond_window, 4);

  lc.max_window_m = 6.0;  // the same uncertainty inside the window: searched every time
  LoopCloser inside(lc, IncrementalConfig{});
  EXPECT_TRUE(inside.SearchLocal(chain.View(), 12, 1, &accepted).has_value());
  EXPECT_EQ(inside.stats().beyond_window, 0);
}

TEST(LoopCloser, TheHookSeesEveryHypothesisBeforeTheVerifier) {
  const Chain chain(Pose2(0.1, 0.1, 0.0));
  LoopCloser closer(Immediate(), IncrementalConfig{});
  int calls = 0;
  closer.set_hypothesis_hook([&](LoopHypothesis* h, const Values& values) {
    ++calls;
    EXPECT_EQ(values.size(), chain.values.size());
    h->injected = true;
  });
  std::vector<LoopHypothesis> accepted;
  closer.SearchLocal(chain.View(), 12, 0, &accepted);
  EXPECT_EQ(calls, 1);
  ASSERT_EQ(accepted.size(), 1u);
  EXPECT_TRUE(accepted.front().injected);
  EXPECT_EQ(closer.stats().injected, 1);
}

TEST(LoopCloser, TheGlobalSearchIsOffByDefault) {
  const Chain chain(Pose2(0.0, 0.0, 0.0));
  LoopCloser closer(Immediate(), IncrementalConfig{});
  std::vector<LoopHypothesis> accepted;
  EXPECT_FALSE(closer.SearchGlobal(chain.View(), 12, true, &accepted).has_value());
  EXPECT_TRUE(accepted.empty());
}

}  // namespace
}  // namespace lifelong::slam
