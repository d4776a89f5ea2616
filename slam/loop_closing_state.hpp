// What loop closing keeps between observations: the closures in the graph, the verifier
// holding the hypotheses, and its counters (a part of Mapper::State; not public API).
#pragma once

#include <vector>

#include "slam/loop_verifier.hpp"
#include "slam/mapper.hpp"

namespace lifelong::slam {

struct LoopClosingState {
  explicit LoopClosingState(const LoopVerifierConfig& config) : verifier(config) {}

  std::vector<LoopClosureRecord> loops;  ///< closures put into the graph, in order
  LoopVerifier verifier;                 ///< closures wait here until a group confirms them
  int hypotheses = 0;                    ///< closures proposed by the matcher so far
  int since_optimize = 0;                ///< closures added since the last optimization
  int since_sync = 0;  ///< closures added since the map was last re-rendered (SyncMap)
};

}  // namespace lifelong::slam
