// `lifelong sweep`, part of the module liblifelong_commands.so (apps/commands.hpp).
#pragma once

#include "apps/commands.hpp"

namespace lifelong::apps {

/// Runs a sweep (or only collects one); exit 0, 1 when a cell failed, 2 bad input, 130.
int SweepCommand(const SweepArgs& args);

}  // namespace lifelong::apps
