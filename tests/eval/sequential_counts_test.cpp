// timeline.csv's `sequential` column and summary.json's `sequential` counts
// (eval/metrics/sequential_counts.hpp).
#include "eval/metrics/sequential_counts.hpp"

#include <string>

#include <gtest/gtest.h>

namespace lifelong::eval {
namespace {

TEST(SequentialCounts, TheFirstObservationIsNotCountedAndARecoveredMatchIsMatched) {
  SequentialSummary counts;
  slam::StepStats first;
  first.observation_index = 0;
  EXPECT_EQ(std::string(SequentialOutcome(first)), "first");
  CountSequential(first, &counts);
  EXPECT_EQ(counts.count, 0);

  slam::StepStats recovered;
  recovered.observation_index = 1;
  recovered.incremental_match_ok = true;
  recovered.incremental_match_recovered = true;
  EXPECT_EQ(std::string(SequentialOutcome(recovered)), "matched");
  CountSequential(recovered, &counts);

  slam::StepStats weak;
  weak.observation_index = 2;
  weak.incremental_match_weak = true;
  EXPECT_EQ(std::string(SequentialOutcome(weak)), "weak");
  CountSequential(weak, &counts);

  slam::StepStats failed;
  failed.observation_index = 3;
  EXPECT_EQ(std::string(SequentialOutcome(failed)), "odometry");
  CountSequential(failed, &counts);

  EXPECT_EQ(counts.count, 3);
  EXPECT_EQ(counts.matched, 1);
  EXPECT_EQ(counts.recovered, 1);
  EXPECT_EQ(counts.weak, 1);
  EXPECT_EQ(counts.degenerate, 0);
}

}  // namespace
}  // namespace lifelong::eval
