// `lifelong sweep`, part of the module liblifelong_commands.so (apps/commands.hpp).
#pragma once

#include <string>

#include "apps/commands.hpp"
#include "eval/sweep/sweep_run.hpp"

namespace lifelong::apps {

/// Runs a sweep (or only collects one); exit 0, 1 when a cell failed, 2 bad input, 130.
int SweepCommand(const SweepArgs& args);

/// How this program runs the sweep of `spec` into `out`: its cells run this binary (its
/// version and commit in every cell's hash), `jobs` at once (0: the number of cores), with
/// progress on stderr.
eval::SweepOptions SweepOptionsFor(const std::string& spec, const std::string& out, int jobs);

}  // namespace lifelong::apps
