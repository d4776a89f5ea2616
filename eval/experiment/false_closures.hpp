// The false-closure test (loops.inject_false_*): a hypothesis hook (Mapper::set_hypothesis_hook)
// that moves every 1/share-th loop-closure hypothesis by (dx, dy) in the world frame before
// verification, as a closure into the neighbouring aisle would be, and marks it injected, so
// that the verifier's and the back-end's defences can be measured against known wrong ones.
#pragma once

#include <functional>

#include "slam/loops/loop_verifier.hpp"

namespace lifelong::eval {

/// The hook for `share` in (0, 1] (nothing is moved at 0), deterministic: the n-th hypothesis
/// (0-based) is moved when floor((n + 1) share) steps up from floor(n share).
std::function<void(slam::LoopHypothesis*, const slam::Values&)> FalseClosureInjector(double share,
                                                                                     double dx_m,
                                                                                     double dy_m);

}  // namespace lifelong::eval
