// Configuration of the mapper facade: one struct with defaults, handed down (KISS-ICP style).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "slam/backend/optimizer.hpp"
#include "slam/grid/grid_map.hpp"
#include "slam/loops/loop_config.hpp"
#include "slam/mapping/mode.hpp"
#include "slam/marginal/marginalization.hpp"
#include "slam/matching/incremental_config.hpp"
#include "slam/removal/removal_policy.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {

struct KeyframeConfig {
  /// An observation is taken after this much motion... On freiburg-079 and the freiburg campus
  /// real odometry drifts past the matcher's window within 0.5 m; 0.25 m (and 0.2 rad) maps
  /// them, but costs the simulated scenarios ATE and time (docs/results.md "Sequential matching
  /// on real odometry"), so it is not the default.
  double min_translation_m = 0.5;
  double min_rotation_rad = 0.35;  ///< ...or this much turning (odometry)
};

struct PruningConfig {
  /// The mode (mode.hpp): chosen with --modes, never in a config file.
  Mode mode;
  /// Remove while the lowest gain is <= this, bits. The seed (§5.1) uses 0; 5 bits, about five
  /// cells no other scan sees, keeps range-noise speckle from growing the graph.
  double gain_threshold_bits = 5.0;
  double radius_m = 6.0;      ///< neighbourhood (Dijkstra expansion) considered
  int keep_recent_nodes = 3;  ///< the newest nodes are never removed
  /// Prune at every n-th graph node (1: at every one, the seed's rule). Larger trades the
  /// information gains' cost (most of pruned's overhead on short runs) for nodes kept a
  /// little longer (docs/results.md "Pruning every n-th node").
  int round_period = 1;
  int node_budget = 0;  ///< > 0: remove the lowest gain past this many nodes
  /// > 0 (Chow-Liu mode): when the graph holds more edges than this per node, the edges in
  /// a node's Markov blanket (or two-hop neighbourhood) are replaced by their Chow-Liu tree
  /// (this project's extension of the seed: a bound on edges as node_budget is one on
  /// nodes). 0: off.
  double max_edges_per_node = 2.0;
  /// Chow-Liu: also fold the edges among the removed node's neighbours into the tree.
  BlanketPolicy blanket = BlanketPolicy::kBlanket;
  /// nfr-subgraph: which pairs beyond the tree may get an edge, and how many per clique
  /// (SparsifierConfig).
  NfrChords nfr_chords = NfrChords::kJoined;
  double nfr_chord_ratio = 1.0;
  /// Where the new factors' measurements put their minimum (sparsifier.hpp "Means"): at the
  /// estimate (zero residual, the seed), or moved to keep the exact marginal's gradient or
  /// mean, so the pull of measurements the estimate has not yet followed survives a removal.
  /// Default, with robust_marginal (docs/results.md "Where a removal puts its factors' minimum").
  FactorMeans factor_means = FactorMeans::kMarginalMean;
  /// A loop edge enters a removal's marginal with the weight the optimizer's robust kernel
  /// gives it at the estimate (its IRLS weight), as in the objective the optimizer minimizes.
  /// false: with its full information (the seed).
  bool robust_marginal = true;
  /// The overlap rule's settings (slam_toolbox's defaults).
  OverlapRuleConfig overlap;
  /// The DPG rule's settings (removal_policy_dpg.cpp).
  DpgRuleConfig dpg;
};

/// The mapper's back-end: warm-started Gauss-Newton with a robust Cauchy kernel on the loop
/// edges. Near the optimum it needs no damping, and every LM trial step costs a
/// factorization (3x the back-end time on corridor_100, measured at 98ec146 on 2026-11-22).
inline OptimizerParams OnlineOptimizerParams() {
  OptimizerParams p;
  p.method = OptimizerMethod::kGaussNewton;
  p.max_iterations = 5;
  p.evaluate_final_chi2 = false;
  p.relative_tolerance = 1e-5;
  p.robust_kernel = RobustKernel::kCauchy;
  p.robust_delta = 3.0;
  p.linear_initialization = false;  // warm-started from the previous optimum
  return p;
}

/// Every setting of the mapper, with its default: configs/default.yaml sets each key to the
/// value here (a test keeps them equal). Allowed values: mapper_config_fields.hpp.
struct MapperConfig {
  KeyframeConfig keyframes;
  IncrementalConfig incremental;
  LoopClosingConfig loops;
  PruningConfig pruning;
  GridMapConfig grid;
  OptimizerParams optimizer = OnlineOptimizerParams();
  double map_move_epsilon_m = 0.01;     ///< re-render a scan when its node moved this much...
  double map_move_epsilon_rad = 0.005;  ///< ...or turned this much
};

/// A setting outside its allowed values: the dotted field(s) and why.
struct ConfigProblem {
  std::string fields;
  std::string message;
  /// For a bound between two settings (a minimum above its maximum), `fields` names the upper
  /// one and this the lower: a reader blames this one when a file gives it and not the other.
  std::string counterpart = {};
};

/// The first setting of `config` outside its allowed values (mapper_config_fields.hpp), or a
/// combination whose matcher tables or place descriptors would exceed their memory bounds;
/// nothing when it is valid. The Mapper refuses an invalid config.
std::optional<ConfigProblem> Validate(const MapperConfig& config);

}  // namespace lifelong::slam
