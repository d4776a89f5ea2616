// summary.json's loop-closure figures: loop_verification (its injected counts only when the
// false-closure test was on) and loop_precision_last_hour.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "eval/metrics/summary.hpp"

namespace lifelong::eval {
namespace {

nlohmann::json ModeJsonOf(const ModeSummary& m) {
  RunSummary s;
  s.modes["pruned"] = m;
  return nlohmann::json::parse(SummaryJsonText(s))["modes"]["pruned"];
}

TEST(LoopSummary, VerificationCountsWithoutInjection) {
  ModeSummary m;
  m.loop_verification =
      LoopVerificationSummary{{40, 31, 2, 7, 5, 0, 0, 64, 3, 10, 4, 2}, false, false, 2};
  const auto j = ModeJsonOf(m)["loop_verification"];
  EXPECT_EQ(j["proposed"], 40);
  EXPECT_EQ(j["accepted"], 31);
  EXPECT_EQ(j["rejected"], 2);
  EXPECT_EQ(j["expired"], 7);
  EXPECT_EQ(j["not_unique"], 5);
  EXPECT_EQ(j["switched_off"], 2);
  EXPECT_EQ(j["attempts"], 64);
  EXPECT_EQ(j["few_points"], 3);
  EXPECT_EQ(j["low_score"], 10);
  EXPECT_EQ(j["ambiguous"], 4);
  EXPECT_EQ(j["implausible"], 2);
  EXPECT_FALSE(j.contains("injected"));  // not a silent zero: the test was off
  EXPECT_FALSE(ModeJsonOf(m).contains("loop_precision_last_hour"));
}

TEST(LoopSummary, InjectedCountsWhenTheTestWasOn) {
  ModeSummary m;
  m.loop_verification = LoopVerificationSummary{{40, 31, 2, 7, 5, 3, 0}, true, false, 0};
  m.loop_precision_last_hour = 0.995;
  const auto j = ModeJsonOf(m);
  EXPECT_EQ(j["loop_verification"]["injected"], 3);
  EXPECT_EQ(j["loop_verification"]["injected_accepted"], 0);
  EXPECT_DOUBLE_EQ(j["loop_precision_last_hour"].get<double>(), 0.995);
}

}  // namespace
}  // namespace lifelong::eval
