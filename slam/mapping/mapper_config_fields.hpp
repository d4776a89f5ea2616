// Every mapper setting once, with its key and its allowed values: the Visit* functions walk
// the MapperConfig, calling the visitor's Section, Number, Int, PowerOfTwo, Bool, Enum and
// Ordered for each key. Three visitors walk them: the range Checker (config_checker.hpp),
// and eval's config file reader and writer, which only map keys to fields and back.
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "slam/mapping/mapper_config.hpp"
#include "slam/removal/removal_policy.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam::config_fields {

using slam::LinearSolver;
using slam::OptimizerMethod;
using slam::RobustKernel;

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// Allowed values of a number: [min, max], or (min, max] when min_open; when zero_or_from is
/// set, 0 or [zero_or_from, max] (0 meaning "automatic").
struct Range {
  double min;
  double max;
  bool min_open;
  const char* text;
  double zero_or_from = 0.0;
  /// Whether v is an allowed value (finite, and inside the range).
  bool Admits(double v) const {
    const bool below =
        (min_open ? v <= min : v < min) || (zero_or_from > 0.0 && v != 0.0 && v < zero_or_from);
    return std::isfinite(v) && !below && v <= max;
  }
};
inline constexpr Range kAnyNumber{-kInf, kInf, false, "a finite number"};
inline constexpr Range kNonNegative{0.0, kInf, false, ">= 0"};
inline constexpr Range kPositive{0.0, kInf, true, "> 0"};
inline constexpr Range kUnit{0.0, 1.0, false, "in [0, 1]"};
/// A Weibull shape: past 100, exp(-(dt / tau)^k) is a step at tau to the last bit anyway.
inline constexpr Range kShape{1.0, 100.0, false, "in [1, 100]"};
/// Cell sides: a finer cell than 5 mm resolves nothing a laser measures, and costs memory and
/// time by the square (1e-6 m filled 24 GB in one scan).
inline constexpr Range kCellSide{0.005, 10.0, false, "in [0.005, 10] m"};
/// Search windows and steps: a matcher's table and its list of headings grow with them, and
/// past these they exhausted memory (a window of 1e6 m, a heading step of 1e-9 rad).
inline constexpr Range kWindowM{0.0, 50.0, true, "in (0, 50] m"};
inline constexpr Range kWindowRad{0.0, 3.14159265358979323846, true, "in (0, pi] rad"};
inline constexpr Range kAngularStep{0.0, 0.5, false, "0 (automatic) or in [1e-4, 0.5] rad", 1e-4};

template <class E>
struct EnumName {
  const char* name;
  E value;
};
inline constexpr EnumName<OptimizerMethod> kMethods[] = {
    {"lm", OptimizerMethod::kLevenbergMarquardt}, {"gn", OptimizerMethod::kGaussNewton}};
inline constexpr EnumName<RobustKernel> kKernels[] = {{"none", RobustKernel::kNone},
                                                      {"huber", RobustKernel::kHuber},
                                                      {"cauchy", RobustKernel::kCauchy},
                                                      {"dcs", RobustKernel::kDcs}};
inline constexpr EnumName<LinearSolver> kSolvers[] = {{"auto", LinearSolver::kAuto},
                                                      {"simplicial", LinearSolver::kSimplicial},
                                                      {"supernodal", LinearSolver::kSupernodal}};
inline constexpr EnumName<slam::NfrChords> kNfrChords[] = {
    {"joined", slam::NfrChords::kJoined},
    {"mutual_information", slam::NfrChords::kMutualInformation}};
inline constexpr EnumName<slam::FactorMeans> kFactorMeans[] = {
    {"estimate", slam::FactorMeans::kEstimate},
    {"gradient", slam::FactorMeans::kGradient},
    {"marginal_mean", slam::FactorMeans::kMarginalMean}};
inline constexpr EnumName<slam::BlanketPolicy> kBlankets[] = {
    {"factors_at_node", slam::BlanketPolicy::kFactorsAtK},
    {"markov_blanket", slam::BlanketPolicy::kBlanket}};

// ---- Every setting, once. The reader and the writer both walk these lists. ----

template <class V>
void VisitMatcher(V& v, slam::MatcherConfig& m, bool with_windows) {
  if (with_windows) {
    v.Number("linear_window_m", m.linear_window_m, kWindowM);
    v.Number("angular_window_rad", m.angular_window_rad, kWindowRad);
  }
  v.Number("resolution_m", m.resolution_m, kCellSide);
  v.Number("angular_step_rad", m.angular_step_rad, kAngularStep);
  v.PowerOfTwo("coarse_factor", m.coarse_factor);
  v.Number("sigma_m", m.sigma_m, kPositive);
  v.Number("min_score", m.min_score, kUnit);
  v.Number("ambiguity_radius_m", m.ambiguity_radius_m, kNonNegative);
  v.Number("ambiguity_angle_rad", m.ambiguity_angle_rad, kNonNegative);
  v.Number("floor_sigma_m", m.floor_sigma_m, kNonNegative);
  v.Number("floor_sigma_rad", m.floor_sigma_rad, kNonNegative);
  v.Bool("refine", m.refine);
}

template <class V>
void VisitIncremental(V& v, slam::IncrementalConfig& c) {
  v.Int("local_map_nodes", c.local_map_nodes, 1);
  // Finer thinning than a matcher cell only multiplies the points (1e-9 m exhausted memory).
  v.Number("point_spacing_m", c.point_spacing_m,
           Range{0.0, 1.0, false, "0 (no thinning) or in [0.005, 1] m", 0.005});
  v.Number("surface_gap_m", c.surfaces.gap_m, kNonNegative);
  v.Number("surface_line_gap_m", c.surfaces.line_gap_m, kNonNegative);
  v.Number("surface_line_tol_m", c.surfaces.line_tol_m, kPositive);
  v.Section("matcher", [&](auto& s) { VisitMatcher(s, c.matcher, true); });
  v.Number("odom_sigma_xy_m", c.odom_sigma_xy_m, kPositive);
  v.Number("odom_sigma_xy_per_m", c.odom_sigma_xy_per_m, kNonNegative);
  v.Number("odom_sigma_rad", c.odom_sigma_rad, kPositive);
  v.Number("odom_sigma_rad_per_rad", c.odom_sigma_rad_per_rad, kNonNegative);
  v.Number("max_ambiguity", c.max_ambiguity, kUnit);
  v.Number("weak_score", c.weak_score, kUnit);
  v.Number("weak_max_ambiguity", c.weak_max_ambiguity, kUnit);
  v.Number("lost_window_m", c.lost_window_m, Range{0.0, 50.0, true, "in (0, 50] m"});
  v.Number("recovery_window_m", c.recovery_window_m, Range{0.0, 50.0, false, "in [0, 50] m"});
  v.Bool("recover_past_odometry", c.recover_past_odometry);
  v.Number("between_refine_m", c.between_refine_m, Range{0.0, 1.0, false, "in [0, 1] m"});
  v.Number("between_refine_rad", c.between_refine_rad, Range{0.0, 1.0, false, "in [0, 1] rad"});
}

template <class V>
void VisitVerify(V& v, slam::LoopVerifierConfig& c) {
  v.Bool("enabled", c.enabled);
  v.Int("min_group", c.min_group, 1);
  v.Number("consistency_chi2", c.consistency_chi2, kPositive);
  v.Number("window_m", c.window_m, kNonNegative);
  v.Number("expiry_m", c.expiry_m, kNonNegative);
  v.Number("base_var_xy_m2", c.base_var_xy_m2, kPositive);
  v.Number("var_xy_per_m", c.var_xy_per_m, kNonNegative);
  v.Number("base_var_rad2", c.base_var_rad2, kPositive);
  v.Number("var_rad_per_m", c.var_rad_per_m, kNonNegative);
}

template <class V>
void VisitGlobal(V& v, slam::GlobalLoopConfig& g) {
  v.Bool("enabled", g.enabled);
  // Each bounded: a search matches `candidates` places and compares `index_neighbours` in
  // full, and a descriptor holds rings x sectors bins for every node.
  v.Int("every", g.every, 1);
  v.Number("after_m", g.after_m, kNonNegative);
  v.Int("candidates", g.candidates, 1, 100);
  v.Int("index_neighbours", g.index_neighbours, 1, 10000);
  v.Number("max_distance", g.max_distance, kUnit);
  v.Int("min_occupied", g.min_occupied, 0);
  v.Int("context_nodes", g.context_nodes, 0, 1000);
  v.Number("lateral_step_m", g.lateral_step_m, kPositive);
  v.Int("lateral_steps", g.lateral_steps, 0, 20);
  v.Number("linear_window_m", g.linear_window_m, kWindowM);
  v.Number("angular_window_rad", g.angular_window_rad, kWindowRad);
  v.Number("submap_travel_m", g.submap_travel_m, kNonNegative);
  v.Number("near_range_m", g.near_range_m, kNonNegative);
  v.Number("follow_m", g.follow_m, kNonNegative);
  v.Number("plausible_sigmas", g.plausible_sigmas, kPositive);
  v.Int("rings", g.descriptor.rings, 1, 1000);
  v.Int("sectors", g.descriptor.sectors, 4, 3600);
  v.Number("max_range_m", g.descriptor.max_range_m, kPositive);
}

template <class V>
void VisitLoops(V& v, slam::LoopClosingConfig& c) {
  v.Bool("enabled", c.enabled);
  v.Number("min_path_separation_m", c.min_path_separation_m, kNonNegative);
  v.Number("overlap_radius_m", c.overlap_radius_m, kNonNegative);
  v.Number("gate_chi2", c.gate_chi2, kPositive);
  v.Number("max_position_sigma_m", c.max_position_sigma_m, kPositive);
  v.Number("min_window_m", c.min_window_m, kWindowM);
  v.Number("max_window_m", c.max_window_m, kWindowM);
  v.Ordered("min_window_m", c.min_window_m, "max_window_m", c.max_window_m);
  v.Number("min_window_rad", c.min_window_rad, kWindowRad);
  v.Number("max_window_rad", c.max_window_rad, kWindowRad);
  v.Ordered("min_window_rad", c.min_window_rad, "max_window_rad", c.max_window_rad);
  v.Int("beyond_window_every", c.beyond_window_every, 0);
  v.Int("neighbours_per_candidate", c.neighbours_per_candidate, 0);
  v.Int("submap_span", c.submap_span, 0);
  v.Number("min_score", c.min_score, kUnit);
  v.Number("max_ambiguity", c.max_ambiguity, kUnit);
  v.Number("max_flatness", c.max_flatness, kUnit);
  v.Number("uniqueness_radius_m", c.uniqueness_radius_m, kPositive);
  v.Number("context_ambiguity", c.context_ambiguity, kUnit);
  v.Number("context_span_m", c.context_span_m, kPositive);
  v.Number("refine_window_m", c.refine_window_m, Range{0.0, 50.0, false, "in [0, 50] m"});
  v.Number("refine_window_rad", c.refine_window_rad, kWindowRad);
  v.Number("consistency_chi2", c.consistency_chi2, kPositive);
  v.Int("min_reference_points", c.min_reference_points, 0);
  v.Bool("measure_low_scores", c.measure_low_scores);
  v.Bool("surfaces", c.surfaces);
  v.Bool("surface_lines", c.surface_lines);
  v.Section("matcher", [&](auto& s) { VisitMatcher(s, c.matcher, false); });
  v.Number("optimize_edge_chi2", c.optimize_edge_chi2, kNonNegative);
  v.Int("optimize_every", c.optimize_every, 1);
  v.Section("verify", [&](auto& s) { VisitVerify(s, c.verify); });
  v.Section("global", [&](auto& s) { VisitGlobal(s, c.global); });
  v.Number("suspect_chi2", c.suspect_chi2, kPositive);
}

template <class V>
void VisitOptimizer(V& v, slam::OptimizerParams& p) {
  v.Enum("method", p.method, kMethods);
  v.Int("max_iterations", p.max_iterations, 1);
  v.Number("relative_tolerance", p.relative_tolerance, kNonNegative);
  v.Number("step_tolerance", p.step_tolerance, kNonNegative);
  v.Number("absolute_tolerance", p.absolute_tolerance, kNonNegative);
  v.Enum("robust_kernel", p.robust_kernel, kKernels);
  v.Number("robust_delta", p.robust_delta, kPositive);
  v.Bool("scale_damping", p.scale_damping);
  v.Number("initial_lambda_factor", p.initial_lambda_factor, kPositive);
  v.Bool("evaluate_final_chi2", p.evaluate_final_chi2);
  v.Bool("linear_initialization", p.linear_initialization);
  v.Enum("linear_solver", p.linear_solver, kSolvers);
}

template <class V>
void VisitConfig(V& v, slam::MapperConfig& c) {
  v.Section("keyframes", [&](auto& s) {
    s.Number("min_translation_m", c.keyframes.min_translation_m, kNonNegative);
    s.Number("min_rotation_rad", c.keyframes.min_rotation_rad, kNonNegative);
  });
  v.Section("incremental", [&](auto& s) { VisitIncremental(s, c.incremental); });
  v.Section("loops", [&](auto& s) { VisitLoops(s, c.loops); });
  v.Section("pruning", [&](auto& s) {
    s.Number("gain_threshold_bits", c.pruning.gain_threshold_bits, kAnyNumber);
    s.Number("radius_m", c.pruning.radius_m, kNonNegative);
    s.Int("keep_recent_nodes", c.pruning.keep_recent_nodes, 0);
    s.Int("round_period", c.pruning.round_period, 1);
    s.Int("node_budget", c.pruning.node_budget, 0);
    s.Number("max_edges_per_node", c.pruning.max_edges_per_node, kNonNegative);
    s.Enum("blanket", c.pruning.blanket, kBlankets);
    s.Section("overlap", [&](auto& o) {
      slam::OverlapRuleConfig& r = c.pruning.overlap;
      o.Number("iou_min", r.iou_min, kUnit);
      o.Number("iou_match", r.iou_match, kUnit);
      o.Number("removal_score", r.removal_score, kUnit);
      o.Number("overlap_scale", r.overlap_scale, kUnit);
      o.Number("constraint_scale", r.constraint_scale, kUnit);
      o.Number("nearby_penalty", r.nearby_penalty, kUnit);
      o.Int("scan_buffer", r.scan_buffer, 0);
    });
    s.Section("dpg", [&](auto& d) {
      slam::DpgRuleConfig& r = c.pruning.dpg;
      d.Number("margin_m", r.detection.margin_m, kNonNegative);
      d.Number("edge_guard_m", r.detection.edge_guard_m, kNonNegative);
      d.Number("min_agreement", r.detection.min_agreement, kUnit);
      d.Number("hidden_m", r.detection.hidden_m, kNonNegative);
      d.Number("min_incidence_rad", r.detection.min_incidence_rad, kNonNegative);
      d.Number("min_incidence_added_rad", r.detection.min_incidence_added_rad, kNonNegative);
      d.Number("added_depth_m", r.detection.added_depth_m, kNonNegative);
      d.Int("min_run_beams", r.detection.min_run_beams, 1);
      d.Int("min_run_occluded_beams", r.detection.min_run_occluded_beams, 0);
      d.Number("min_active_share", r.min_active_share, kUnit);
      d.Number("compare_radius_m", r.compare_radius_m, kNonNegative);
      d.Number("min_agreement_vouched", r.min_agreement_vouched, kUnit);
    });
    s.Enum("nfr_chords", c.pruning.nfr_chords, kNfrChords);
    s.Number("nfr_chord_ratio", c.pruning.nfr_chord_ratio, kNonNegative);
    s.Enum("factor_means", c.pruning.factor_means, kFactorMeans);
    s.Bool("robust_marginal", c.pruning.robust_marginal);
  });
  v.Section("grid", [&](auto& s) {
    s.Number("resolution_m", c.grid.resolution_m, kCellSide);
    s.Number("max_free_range_m", c.grid.max_free_range_m, kNonNegative);
    s.Number("max_hit_range_m", c.grid.max_hit_range_m, kPositive);
    s.Int("max_dropout_beams", c.grid.max_dropout_beams, 0);
    s.Bool("hits_mask_own_misses", c.grid.hits_mask_own_misses);
    s.Number("present_timescale_s", c.grid.present_timescale_s, kNonNegative);
    s.Number("present_shape", c.grid.present_shape, kShape);
  });
  v.Section("optimizer", [&](auto& s) { VisitOptimizer(s, c.optimizer); });
  v.Section("map_update", [&](auto& s) {
    s.Number("map_move_epsilon_m", c.map_move_epsilon_m, kNonNegative);
    s.Number("map_move_epsilon_rad", c.map_move_epsilon_rad, kNonNegative);
  });
}

/// Shortest text that reads back to exactly `v`, with a ".0" on integral values.
inline std::string ShortestDouble(double v) {
  char buf[64];
  const auto result = std::to_chars(buf, buf + sizeof(buf), v);
  std::string s(buf, result.ptr);
  if (std::isfinite(v) && s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

}  // namespace lifelong::slam::config_fields
