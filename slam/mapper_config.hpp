// Configuration of the mapper facade: one struct with defaults, handed down (KISS-ICP style).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "slam/grid_map.hpp"
#include "slam/loop_verifier.hpp"
#include "slam/marginalization.hpp"
#include "slam/optimizer.hpp"
#include "slam/place_descriptor.hpp"
#include "slam/removal_policy.hpp"
#include "slam/scan_matcher.hpp"
#include "slam/sparsifier.hpp"

namespace lifelong::slam {

/// How (and whether) the mapper removes nodes: a mode names a removal policy and a
/// sparsifier (DESIGN.md "Methods as parts"); kNone is the standard approach.
enum class PruningMode : std::uint8_t {
  kNone,     ///< `standard`: never removes a node
  kChowLiu,  ///< `pruned`: information gain + Chow-Liu tree marginalization (the seed)
  kExact,    ///< `pruned-exact`: the same removal, exact marginalization (dense cliques)
  kNaive,    ///< `pruned-naive`: delete and reconnect by composing constraints
  kGlc,      ///< `pruned-glc`: the same removal, sparse GLC factors (glc.hpp)
  kNfr,      ///< `pruned-nfr`: the same removal, NFR on the tree and joined pairs (nfr.hpp)
  kOverlap,  ///< `pruned-overlap`: slam_toolbox's overlap rule picks the node, Chow-Liu trees
  kDpg,      ///< `pruned-dpg`: DPG-SLAM's change detection retires beams and nodes, Chow-Liu
};

/// Parses a mode's name (PruningModeNames); false when unknown.
bool ParsePruningMode(const std::string& name, PruningMode* mode);
std::string PruningModeName(PruningMode mode);
/// Every mode's name: standard, pruned, pruned-exact, ...
std::vector<std::string> PruningModeNames();
/// The names joined by ", ", for error messages and help.
std::string PruningModeList();
/// The sparsifier (sparsifier.hpp) a mode uses when pruning.sparsifier does not name one;
/// empty for kNone.
std::string ModeSparsifier(PruningMode mode);
/// The removal policy (removal_policy.hpp) a mode uses; empty: pruning.policy's.
std::string ModePolicy(PruningMode mode);

struct KeyframeConfig {
  /// An observation is taken after this much motion... On freiburg-079 and the freiburg campus
  /// real odometry drifts past the matcher's window within 0.5 m; 0.25 m (and 0.2 rad) maps
  /// them, but costs the simulated scenarios ATE and time (BENCHMARKS.md "Sequential matching
  /// on real odometry"), so it is not the default.
  double min_translation_m = 0.5;
  double min_rotation_rad = 0.35;  ///< ...or this much turning (odometry)
};

/// The incremental matcher's window and acceptance (its table and field are the matcher's
/// defaults). Real odometry turns by more than a simulated one between observations, and the
/// mean likelihood of a match in a wide hall, whose returns lie far apart, is low: a 0.26 rad
/// window and a 0.5 score failed one match in three on acapulco and edmonton and bent csail
/// (BENCHMARKS.md "Sequential matching on real odometry"). The linear window stays 0.3 m: at
/// 0.5 m the matcher slips along the simulated corridors.
inline MatcherConfig IncrementalMatcherDefaults() {
  MatcherConfig m;
  m.angular_window_rad = 0.5;
  m.min_score = 0.3;
  return m;
}

struct IncrementalConfig {
  /// Recent nodes whose scans form the local map: 20 nodes cover about 10 m of path (8, before
  /// 2026-12-04, covered 4 m, too little to hold a heading through a room on real odometry).
  int local_map_nodes = 20;
  double point_spacing_m = 0.05;  ///< voxel thinning of matched points
  /// The local map joins consecutive returns of a scan into surfaces (SurfacePoints), so its
  /// likelihood field is smooth along walls hit at grazing angles and motion along them is
  /// not under-measured. YAML keys surface_gap_m (0: return points, before 2026-12-02),
  /// surface_line_gap_m and surface_line_tol_m (the line rule; gap 0: off).
  SurfaceRule surfaces;
  MatcherConfig matcher = IncrementalMatcherDefaults();  ///< window around the odometry guess
  double odom_sigma_xy_m = 0.05;     ///< fallback edge when matching fails: base sigma
  double odom_sigma_xy_per_m = 0.1;  ///< ...plus this much per metre travelled
  double odom_sigma_rad = 0.02;      ///< ...heading base sigma
  double odom_sigma_rad_per_rad = 0.1;
  /// A match whose best distinct rival scores above this share of it does not measure the
  /// direction towards the rival: the odometry does (slam/match_degeneracy.hpp). 1: off, the
  /// match alone (before 2026-12-04).
  double max_ambiguity = 0.95;
};

/// Global loop closing (slam/loop_closer_global.cpp): where the local search, gated by the
/// projected uncertainty, finds nothing, the node's place descriptor (Scan Context,
/// slam/place_descriptor.hpp) proposes the most similar earlier places wherever the estimate
/// puts them; each is matched in a wide window around the heading the descriptor gives, and
/// goes through the same acceptance and group verification as a local closure.
struct GlobalLoopConfig {
  bool enabled = false;
  int every = 5;               ///< observations between searches (when no local closure)
  int candidates = 3;          ///< places matched per search, most similar first
  int index_neighbours = 25;   ///< ring-key neighbours compared in full per search
  double max_distance = 0.35;  ///< descriptor distance in [0, 1]: farther is no candidate
  int min_occupied = 30;       ///< descriptor bins: sparser places are neither indexed nor searched
  int context_nodes = 10;      ///< recent nodes whose points, with the node's, make its place
  double linear_window_m = 4.0;     ///< m, search half-width around the candidate's position
  double angular_window_rad = 0.2;  ///< rad, around the descriptor's heading
  /// A match within reach of the covariance projection must lie within this many of its
  /// sigmas of the estimate (the local search's consistency gate, widened).
  double plausible_sigmas = 3.0;
  PlaceDescriptorConfig descriptor;
};

/// The loop closer's matcher: a finer table and a wider likelihood field than the
/// incremental one's (its windows are set per attempt).
inline MatcherConfig LoopMatcherDefaults() {
  MatcherConfig m;
  m.resolution_m = 0.05;
  m.sigma_m = 0.08;
  return m;
}

struct LoopClosingConfig {
  bool enabled = true;
  double min_path_separation_m = 6.0;  ///< nodes closer along the graph are not candidates
  double overlap_radius_m = 1.0;       ///< sensor overlap added to the position uncertainty
  double gate_chi2 = 5.99;             ///< 95 % gate (2 dof) of the candidate test
  double max_position_sigma_m = 20.0;  ///< Dijkstra projection stops beyond this
  double min_window_m = 0.3;           ///< search window: 3 sigma, clamped to [min, max]
  double max_window_m = 6.0;
  double min_window_rad = 0.15;
  double max_window_rad = 0.5;
  /// Candidates whose position uncertainty (3 sigma) exceeds max_window_m are searched, in
  /// the clamped window, at every this many observations (and at every one while hypotheses
  /// wait for confirmation); in between, an observation searches only the candidates its
  /// windows cover. 1: at every observation; 0: never. The pruned graph projects wider
  /// uncertainties than the full one, so most of pruned's searches grow to the largest
  /// window: 5 makes pruned's loop closing cheaper than standard's on freiburg-079, but
  /// loses closures on logs it was not tuned on (acapulco, the infinite corridor), so the
  /// default stays 1 (BENCHMARKS.md "Loop closing's cost by mode").
  int beyond_window_every = 1;
  int neighbours_per_candidate = 2;  ///< graph neighbours of each candidate in the submap
  /// The submap is made of its nodes' surfaces, by the incremental matcher's rule
  /// (IncrementalConfig::surfaces), rather than of their return points (false before
  /// 2026-12-02).
  bool surfaces = true;
  /// ...joined along lines as well (SurfaceRule::line_gap_m), or by the gap alone.
  bool surface_lines = true;
  /// The submap holds one visit: candidates observed within this many observations of the
  /// most likely candidate (and their neighbours alike). 0: every candidate.
  int submap_span = 0;
  double min_score = 0.6;       ///< a good match...
  double max_ambiguity = 0.85;  ///< ...and an unambiguous one...
  /// ...and a locally unique one: no pose uniqueness_radius_m away (8 directions, same
  /// heading) scores above max_flatness times the best. 1: off.
  double max_flatness = 0.9;
  double uniqueness_radius_m = 0.25;
  /// The edge is measured against the attached node's scan alone, in this window around
  /// the submap's answer (0: the submap match is the edge).
  double refine_window_m = 0.0;
  double refine_window_rad = 0.05;
  double consistency_chi2 = 16.27;  ///< 99.9 % gate (3 dof) of the correction
  int min_reference_points = 60;    ///< submap points the search can reach, fewer: no match
  MatcherConfig matcher = LoopMatcherDefaults();  ///< windows are set per attempt
  double optimize_edge_chi2 = 9.0;  ///< optimize at once when the new edge's chi2 exceeds
  int optimize_every = 10;          ///< ...and at least every this many closures
  /// Group verification: a closure enters the graph only once enough others confirm it
  /// (slam/loop_verifier.hpp).
  LoopVerifierConfig verify;
  /// A loop edge whose chi2 at the estimate exceeds this is suspect (its robust kernel is
  /// switching it off): its nodes are neither removed nor sparsified, so that no
  /// marginal bakes it in.
  double suspect_chi2 = 16.27;
  /// False-closure test, read by eval (eval/false_closures.hpp), which installs it as the
  /// mapper's hypothesis hook: this share of the matcher's closures is moved by (dx, dy) in
  /// the world frame before verification, as a closure into the neighbouring aisle would be.
  /// 0: off.
  double inject_false_share = 0.0;
  double inject_false_dx_m = 0.0;  ///< m, world frame
  double inject_false_dy_m = 3.0;  ///< m, world frame
  GlobalLoopConfig global;
};

struct PruningConfig {
  PruningMode mode = PruningMode::kNone;
  /// Remove while the lowest gain is <= this, bits. The seed (§5.1) uses 0; 5 bits, about five
  /// cells no other scan sees, keeps range-noise speckle from growing the graph.
  double gain_threshold_bits = 5.0;
  double radius_m = 6.0;      ///< neighbourhood (Dijkstra expansion) considered
  int keep_recent_nodes = 3;  ///< the newest nodes are never removed
  /// Prune at every n-th graph node (1: at every one, the seed's rule). Larger trades the
  /// information gains' cost (most of pruned's overhead on short runs) for nodes kept a
  /// little longer (BENCHMARKS.md "Pruning every n-th node").
  int round_period = 1;
  int node_budget = 0;  ///< > 0: remove the lowest gain past this many nodes
  /// > 0 (Chow-Liu mode): when the graph holds more edges than this per node, the edges in
  /// a node's Markov blanket (or two-hop neighbourhood) are replaced by their Chow-Liu tree
  /// (this project's extension of the seed: a bound on edges as node_budget is one on
  /// nodes). 0: off.
  double max_edges_per_node = 2.0;
  /// Chow-Liu: also fold the edges among the removed node's neighbours into the tree.
  BlanketPolicy blanket = BlanketPolicy::kBlanket;
  /// Which node goes (removal_policy.hpp): information-gain (the seed), node-budget,
  /// overlap (slam_toolbox's rule; the mode pruned-overlap picks it whatever this says) or
  /// dpg (DPG-SLAM's change detection; the mode pruned-dpg picks it).
  std::string policy = "information-gain";
  /// What replaces its clique (sparsifier.hpp); empty: the mode's (ModeSparsifier).
  std::string sparsifier;
  /// nfr-subgraph: which pairs beyond the tree may get an edge, and how many per clique
  /// (SparsifierConfig).
  NfrChords nfr_chords = NfrChords::kJoined;
  double nfr_chord_ratio = 1.0;
  /// Where the new factors' measurements put their minimum (sparsifier.hpp "Means"): at the
  /// estimate (zero residual, the seed), or moved to keep the exact marginal's gradient or
  /// mean, so the pull of measurements the estimate has not yet followed survives a removal.
  /// The marginal's mean with robust_marginal is the default (BENCHMARKS.md, issue #16).
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
/// factorization (3x the back-end time on corridor_100, BENCHMARKS.md).
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
};

/// The first setting of `config` outside its allowed values (mapper_config_fields.hpp), or a
/// combination whose matcher tables or place descriptors would exceed their memory bounds;
/// nothing when it is valid. The Mapper refuses an invalid config.
std::optional<ConfigProblem> Validate(const MapperConfig& config);

}  // namespace lifelong::slam
