#include "eval/metrics/sequential_counts.hpp"

namespace lifelong::eval {

const char* SequentialOutcome(const slam::StepStats& s) {
  if (s.observation_index == 0) return "first";
  if (s.incremental_match_ok) return s.incremental_match_degenerate ? "degenerate" : "matched";
  return s.incremental_match_weak ? "weak" : "odometry";
}

void CountSequential(const slam::StepStats& s, SequentialSummary* counts) {
  if (s.observation_index <= 0) return;  // the first, or no observation
  ++counts->count;
  if (s.incremental_match_ok) ++counts->matched;
  if (s.incremental_match_degenerate) ++counts->degenerate;
  if (s.incremental_match_weak) ++counts->weak;
  if (s.incremental_match_recovered) ++counts->recovered;
  if (s.odometry_lost) ++counts->lost;
}

}  // namespace lifelong::eval
