// How each observation's sequential edge came about (slam::StepStats), as timeline.csv's
// `sequential` column and summary.json's `sequential` counts (docs/output-contract.md).
#pragma once

#include "eval/metrics/summary.hpp"
#include "slam/mapping/mapper_records.hpp"

namespace lifelong::eval {

/// "first", "matched", "degenerate", "weak" or "odometry" (TimelineRow::sequential).
const char* SequentialOutcome(const slam::StepStats& s);

/// Adds one observation to the counts; the first observation, with nothing to match
/// against, is not counted.
void CountSequential(const slam::StepStats& s, SequentialSummary* counts);

}  // namespace lifelong::eval
