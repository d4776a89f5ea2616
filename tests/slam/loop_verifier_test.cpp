// Group verification of loop closures (slam/loops/loop_verifier.hpp) on a second pass along a
// corridor: old nodes 0..9 at x = 0..9 m, current nodes 100..109 at the same places, the
// estimate of the second pass drifted by 0.3 m sideways (what a closure corrects).
#include <gtest/gtest.h>

#include <Eigen/LU>

#include "slam/loops/loop_verifier.hpp"

namespace lifelong::slam {
namespace {

Values Corridor() {
  Values v;
  for (int i = 0; i < 10; ++i) {
    v[i] = Pose2(i, 0.0, 0.0);
    v[100 + i] = Pose2(i, 0.3, 0.0);
  }
  return v;
}

// Closure between old node i and current node 100 + i, measured as the true relative pose
// plus `error` (x, y in m).
LoopHypothesis Closure(int i, double error_x = 0.0, double error_y = 0.0) {
  LoopHypothesis h;
  h.old = i;
  h.current = 100 + i;
  h.T_old_current = Pose2(error_x, error_y, 0.0);
  h.information = Eigen::Vector3d(2500.0, 2500.0, 1e4).asDiagonal();  // 2 cm, 0.6 deg
  h.covariance = h.information.inverse();
  h.travelled_m = 100.0 + i;
  return h;
}

TEST(LoopVerifier, CorrectClosuresAreConsistentAWrongAisleIsNot) {
  const LoopVerifier v{LoopVerifierConfig{}};
  const Values values = Corridor();
  EXPECT_TRUE(v.Consistent(Closure(2), Closure(6), values));
  EXPECT_FALSE(v.Consistent(Closure(2), Closure(6, 0.0, 3.0), values));  // neighbouring aisle
  EXPECT_FALSE(v.Consistent(Closure(2), Closure(6, 0.0, 0.8), values));
  // A run of wrong closures along one aliased traversal agrees with itself: the reason
  // accepted closures count as evidence.
  EXPECT_TRUE(v.Consistent(Closure(2, 0.0, 3.0), Closure(6, 0.0, 3.0), values));
}

TEST(LoopVerifier, AClosureWaitsForItsGroup) {
  LoopVerifier v{LoopVerifierConfig{}};
  const Values values = Corridor();
  EXPECT_TRUE(v.Add(Closure(1), values).empty());
  EXPECT_TRUE(v.IsPending(1));
  EXPECT_TRUE(v.IsPending(101));
  EXPECT_TRUE(v.Add(Closure(2), values).empty());
  const auto accepted = v.Add(Closure(3), values);
  ASSERT_EQ(accepted.size(), 3u);  // the group, in the order proposed
  EXPECT_EQ(accepted[0].old, 1);
  EXPECT_EQ(accepted[2].old, 3);
  EXPECT_FALSE(v.IsPending(1));
  // The group now vouches for the next consistent closure at once.
  EXPECT_EQ(v.Add(Closure(4), values).size(), 1u);
  EXPECT_EQ(v.stats().accepted, 4);
}

TEST(LoopVerifier, AWrongClosureAmongConfirmedOnesIsRejected) {
  LoopVerifier v{LoopVerifierConfig{}};
  const Values values = Corridor();
  for (int i = 0; i < 3; ++i) v.Add(Closure(i), values);
  EXPECT_TRUE(v.Add(Closure(5, 0.0, 3.0), values).empty());
  EXPECT_EQ(v.stats().rejected, 1);
  EXPECT_FALSE(v.IsPending(5));
  EXPECT_EQ(v.Add(Closure(6), values).size(), 1u);
}

TEST(LoopVerifier, WrongClosuresThatDisagreeNeverFormAGroup) {
  LoopVerifier v{LoopVerifierConfig{}};
  const Values values = Corridor();
  EXPECT_TRUE(v.Add(Closure(1, 0.0, 3.0), values).empty());
  EXPECT_TRUE(v.Add(Closure(4, 0.0, -3.0), values).empty());
  EXPECT_TRUE(v.Add(Closure(7, 2.0, 0.0), values).empty());
  EXPECT_EQ(v.stats().accepted, 0);
  EXPECT_EQ(v.pending().size(), 3u);
}

TEST(LoopVerifier, UnconfirmedHypothesesExpire) {
  LoopVerifierConfig c;
  c.expiry_m = 5.0;
  LoopVerifier v{c};
  const Values values = Corridor();
  v.Add(Closure(0), values);
  v.Expire(103.0);
  EXPECT_EQ(v.pending().size(), 1u);
  v.Expire(106.0);
  EXPECT_TRUE(v.pending().empty());
  EXPECT_EQ(v.stats().expired, 1);
}

TEST(LoopVerifier, ARemovedNodeTakesItsHypothesesAlong) {
  LoopVerifier v{LoopVerifierConfig{}};
  const Values values = Corridor();
  v.Add(Closure(1), values);
  v.ForgetNode(1);
  EXPECT_FALSE(v.IsPending(101));
}

TEST(LoopVerifier, DisabledAcceptsEveryHypothesisAtOnce) {
  LoopVerifierConfig c;
  c.enabled = false;
  LoopVerifier v{c};
  const Values values = Corridor();
  EXPECT_EQ(v.Add(Closure(5, 0.0, 3.0), values).size(), 1u);
  LoopHypothesis injected = Closure(6);
  injected.injected = true;
  v.Add(injected, values);
  EXPECT_EQ(v.stats().injected, 1);
  EXPECT_EQ(v.stats().injected_accepted, 1);
}

}  // namespace
}  // namespace lifelong::slam
