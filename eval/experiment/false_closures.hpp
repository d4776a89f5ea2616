// The false-closure test (a config file's `false_closures` section, read by
// eval/experiment/mapper_config_file.hpp): a hypothesis hook (Mapper::set_hypothesis_hook)
// that moves every 1/share-th loop-closure hypothesis by (dx, dy) in the world frame before
// verification, as a closure into the neighbouring aisle would be, and marks it injected, so
// that the verifier's and the back-end's defences can be measured against known wrong ones.
#pragma once

#include <functional>
#include <optional>

#include "slam/loops/loop_verifier.hpp"
#include "slam/mapping/mapper_config.hpp"
#include "slam/mapping/mapper_config_fields.hpp"

namespace lifelong::eval {

/// The test's settings: this share of the matcher's closures is moved by (dx_m, dy_m) in the
/// world frame before verification, as a closure into the neighbouring aisle would be. They are
/// eval's, not the mapper's: the SLAM core only calls the hook eval installs.
struct FalseClosureConfig {
  double share = 0.0;  ///< in [0, 1]; 0: off
  double dx_m = 0.0;   ///< m, world frame
  double dy_m = 3.0;   ///< m, world frame
};

/// The section's keys, for the config file's reader and writer (the visitors of
/// slam/mapping/mapper_config_fields.hpp).
template <class V>
void VisitFalseClosures(V& v, FalseClosureConfig& c) {
  v.Number("share", c.share, slam::config_fields::kUnit);
  v.Number("dx_m", c.dx_m, slam::config_fields::kAnyNumber);
  v.Number("dy_m", c.dy_m, slam::config_fields::kAnyNumber);
}

/// The first setting outside its allowed values, named as in a config file
/// ("false_closures.share"), or nothing.
std::optional<slam::ConfigProblem> Validate(const FalseClosureConfig& config);

/// The hook for `share` in (0, 1] (nothing is moved at 0), deterministic: the n-th hypothesis
/// (0-based) is moved when floor((n + 1) share) steps up from floor(n share).
std::function<void(slam::LoopHypothesis*, const slam::Values&)> FalseClosureInjector(double share,
                                                                                     double dx_m,
                                                                                     double dy_m);

}  // namespace lifelong::eval
