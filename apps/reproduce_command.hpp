// `lifelong reproduce`, part of the module liblifelong_commands.so (apps/commands.hpp).
#pragma once

#include "apps/commands.hpp"

namespace lifelong::apps {

/// Runs every experiment of the book as a sweep and writes the book; exit 0, 1 when a cell
/// failed, 2 bad input, 130 interrupted.
int ReproduceCommand(const ReproduceArgs& args);

}  // namespace lifelong::apps
