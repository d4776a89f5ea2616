// The false-closure test's hook: which hypotheses it moves, and where to.
#include "eval/experiment/false_closures.hpp"

#include <vector>

#include <gtest/gtest.h>

namespace lifelong::eval {
namespace {

slam::LoopHypothesis Closure() {
  slam::LoopHypothesis h;
  h.old = 1;
  h.current = 2;
  h.T_old_current = Pose2(1.0, 0.0, 0.0);
  return h;
}

TEST(FalseClosureInjector, MovesEveryNthHypothesisByTheWorldOffset) {
  slam::Values values;
  values[1] = Pose2(2.0, 3.0, 1.5707963267948966);  // heading north
  values[2] = Pose2(2.0, 4.0, 1.5707963267948966);
  const auto hook = FalseClosureInjector(0.5, 0.0, 3.0);
  std::vector<bool> injected;
  for (int n = 0; n < 6; ++n) {
    slam::LoopHypothesis h = Closure();
    hook(&h, values);
    injected.push_back(h.injected);
    if (!h.injected) {
      EXPECT_DOUBLE_EQ(h.T_old_current.x, 1.0);
      continue;
    }
    // The matched pose (2, 4) moved 3 m north in the world: 4 m ahead of the old node.
    const Pose2 moved = values.at(1) * h.T_old_current;
    EXPECT_NEAR(moved.x, 2.0, 1e-9);
    EXPECT_NEAR(moved.y, 7.0, 1e-9);
    EXPECT_NEAR(h.T_old_current.x, 4.0, 1e-9);
  }
  EXPECT_EQ(injected, (std::vector<bool>{false, true, false, true, false, true}));
}

TEST(FalseClosureInjector, ShareZeroMovesNothing) {
  slam::Values values;
  values[1] = Pose2();
  const auto hook = FalseClosureInjector(0.0, 5.0, 5.0);
  for (int n = 0; n < 4; ++n) {
    slam::LoopHypothesis h = Closure();
    hook(&h, values);
    EXPECT_FALSE(h.injected);
    EXPECT_DOUBLE_EQ(h.T_old_current.x, 1.0);
  }
}

}  // namespace
}  // namespace lifelong::eval
