// `lifelong score`, part of the module liblifelong_commands.so (apps/commands.hpp).
#pragma once

#include "apps/commands.hpp"

namespace lifelong::apps {

/// Scores each system against the truth into OUT (summary.json, report.html,
/// trajectories.png); exit 0, 2 on bad input, 130 when interrupted.
int ScoreCommand(const ScoreArgs& args);

}  // namespace lifelong::apps
