// The table `lifelong run` and `lifelong replay` print at the end: one row per mode in
// --modes order (the first is the baseline), headers with units, and each mode's wall
// time and last-10 % time as a ratio to the baseline's. Absent figures show as '-'.
#pragma once

#include <string>

#include "eval/metrics/summary.hpp"

namespace lifelong::eval {

/// The console table of a run's summary; rows follow summary.mode_order (then any mode
/// not listed there, by name).
std::string ConsoleTable(const RunSummary& summary);

}  // namespace lifelong::eval
