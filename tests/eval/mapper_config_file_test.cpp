#include "eval/experiment/mapper_config_file.hpp"

#include <gtest/gtest.h>

#include <string>

#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

using slam::MapperConfig;

void ExpectSameMatcher(const slam::MatcherConfig& a, const slam::MatcherConfig& b) {
  EXPECT_EQ(a.linear_window_m, b.linear_window_m);
  EXPECT_EQ(a.angular_window_rad, b.angular_window_rad);
  EXPECT_EQ(a.resolution_m, b.resolution_m);
  EXPECT_EQ(a.angular_step_rad, b.angular_step_rad);
  EXPECT_EQ(a.coarse_factor, b.coarse_factor);
  EXPECT_EQ(a.sigma_m, b.sigma_m);
  EXPECT_EQ(a.min_score, b.min_score);
  EXPECT_EQ(a.ambiguity_radius_m, b.ambiguity_radius_m);
  EXPECT_EQ(a.ambiguity_angle_rad, b.ambiguity_angle_rad);
  EXPECT_EQ(a.floor_sigma_m, b.floor_sigma_m);
  EXPECT_EQ(a.floor_sigma_rad, b.floor_sigma_rad);
  EXPECT_EQ(a.refine, b.refine);
}

void ExpectSameLoops(const slam::LoopClosingConfig& a, const slam::LoopClosingConfig& b) {
  EXPECT_EQ(a.enabled, b.enabled);
  EXPECT_EQ(a.min_path_separation_m, b.min_path_separation_m);
  EXPECT_EQ(a.overlap_radius_m, b.overlap_radius_m);
  EXPECT_EQ(a.gate_chi2, b.gate_chi2);
  EXPECT_EQ(a.max_position_sigma_m, b.max_position_sigma_m);
  EXPECT_EQ(a.min_window_m, b.min_window_m);
  EXPECT_EQ(a.max_window_m, b.max_window_m);
  EXPECT_EQ(a.min_window_rad, b.min_window_rad);
  EXPECT_EQ(a.max_window_rad, b.max_window_rad);
  EXPECT_EQ(a.neighbours_per_candidate, b.neighbours_per_candidate);
  EXPECT_EQ(a.min_score, b.min_score);
  EXPECT_EQ(a.max_ambiguity, b.max_ambiguity);
  EXPECT_EQ(a.consistency_chi2, b.consistency_chi2);
  EXPECT_EQ(a.min_reference_points, b.min_reference_points);
  EXPECT_EQ(a.surfaces, b.surfaces);
  EXPECT_EQ(a.surface_lines, b.surface_lines);
  EXPECT_EQ(a.measure_low_scores, b.measure_low_scores);
  ExpectSameMatcher(a.matcher, b.matcher);
  EXPECT_EQ(a.optimize_edge_chi2, b.optimize_edge_chi2);
  EXPECT_EQ(a.optimize_every, b.optimize_every);
  EXPECT_EQ(a.submap_span, b.submap_span);
  EXPECT_EQ(a.max_flatness, b.max_flatness);
  EXPECT_EQ(a.uniqueness_radius_m, b.uniqueness_radius_m);
  EXPECT_EQ(a.context_ambiguity, b.context_ambiguity);
  EXPECT_EQ(a.context_span_m, b.context_span_m);
  EXPECT_EQ(a.refine_window_m, b.refine_window_m);
  EXPECT_EQ(a.refine_window_rad, b.refine_window_rad);
  EXPECT_EQ(a.verify.enabled, b.verify.enabled);
  EXPECT_EQ(a.verify.min_group, b.verify.min_group);
  EXPECT_EQ(a.verify.consistency_chi2, b.verify.consistency_chi2);
  EXPECT_EQ(a.verify.window_m, b.verify.window_m);
  EXPECT_EQ(a.verify.expiry_m, b.verify.expiry_m);
  EXPECT_EQ(a.verify.base_var_xy_m2, b.verify.base_var_xy_m2);
  EXPECT_EQ(a.verify.var_xy_per_m, b.verify.var_xy_per_m);
  EXPECT_EQ(a.verify.base_var_rad2, b.verify.base_var_rad2);
  EXPECT_EQ(a.verify.var_rad_per_m, b.verify.var_rad_per_m);
  const slam::GlobalLoopConfig &ga = a.global, &gb = b.global;
  EXPECT_EQ(ga.enabled, gb.enabled);
  EXPECT_EQ(ga.every, gb.every);
  EXPECT_EQ(ga.after_m, gb.after_m);
  EXPECT_EQ(ga.candidates, gb.candidates);
  EXPECT_EQ(ga.index_neighbours, gb.index_neighbours);
  EXPECT_EQ(ga.max_distance, gb.max_distance);
  EXPECT_EQ(ga.min_occupied, gb.min_occupied);
  EXPECT_EQ(ga.context_nodes, gb.context_nodes);
  EXPECT_EQ(ga.lateral_step_m, gb.lateral_step_m);
  EXPECT_EQ(ga.lateral_steps, gb.lateral_steps);
  EXPECT_EQ(ga.linear_window_m, gb.linear_window_m);
  EXPECT_EQ(ga.angular_window_rad, gb.angular_window_rad);
  EXPECT_EQ(ga.submap_travel_m, gb.submap_travel_m);
  EXPECT_EQ(ga.near_range_m, gb.near_range_m);
  EXPECT_EQ(ga.follow_m, gb.follow_m);
  EXPECT_EQ(ga.plausible_sigmas, gb.plausible_sigmas);
  EXPECT_EQ(ga.descriptor.rings, gb.descriptor.rings);
  EXPECT_EQ(ga.descriptor.sectors, gb.descriptor.sectors);
  EXPECT_EQ(ga.descriptor.max_range_m, gb.descriptor.max_range_m);
  EXPECT_EQ(a.suspect_chi2, b.suspect_chi2);
}

void ExpectSameOptimizer(const slam::OptimizerParams& a, const slam::OptimizerParams& b) {
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.max_iterations, b.max_iterations);
  EXPECT_EQ(a.relative_tolerance, b.relative_tolerance);
  EXPECT_EQ(a.step_tolerance, b.step_tolerance);
  EXPECT_EQ(a.absolute_tolerance, b.absolute_tolerance);
  EXPECT_EQ(a.anchor, b.anchor);
  EXPECT_EQ(a.robust_kernel, b.robust_kernel);
  EXPECT_EQ(a.robust_delta, b.robust_delta);
  EXPECT_EQ(a.scale_damping, b.scale_damping);
  EXPECT_EQ(a.initial_lambda_factor, b.initial_lambda_factor);
  EXPECT_EQ(a.evaluate_final_chi2, b.evaluate_final_chi2);
  EXPECT_EQ(a.linear_initialization, b.linear_initialization);
  EXPECT_EQ(a.linear_solver, b.linear_solver);
}

void ExpectSameIncremental(const slam::IncrementalConfig& ia, const slam::IncrementalConfig& ib) {
  EXPECT_EQ(ia.local_map_nodes, ib.local_map_nodes);
  EXPECT_EQ(ia.point_spacing_m, ib.point_spacing_m);
  EXPECT_EQ(ia.surfaces.gap_m, ib.surfaces.gap_m);
  EXPECT_EQ(ia.surfaces.line_gap_m, ib.surfaces.line_gap_m);
  EXPECT_EQ(ia.surfaces.line_tol_m, ib.surfaces.line_tol_m);
  ExpectSameMatcher(ia.matcher, ib.matcher);
  EXPECT_EQ(ia.odom_sigma_xy_m, ib.odom_sigma_xy_m);
  EXPECT_EQ(ia.odom_sigma_xy_per_m, ib.odom_sigma_xy_per_m);
  EXPECT_EQ(ia.odom_sigma_rad, ib.odom_sigma_rad);
  EXPECT_EQ(ia.odom_sigma_rad_per_rad, ib.odom_sigma_rad_per_rad);
  EXPECT_EQ(ia.max_ambiguity, ib.max_ambiguity);
  EXPECT_EQ(ia.weak_score, ib.weak_score);
  EXPECT_EQ(ia.weak_max_ambiguity, ib.weak_max_ambiguity);
  EXPECT_EQ(ia.lost_window_m, ib.lost_window_m);
  EXPECT_EQ(ia.recovery_window_m, ib.recovery_window_m);
  EXPECT_EQ(ia.recover_past_odometry, ib.recover_past_odometry);
  EXPECT_EQ(ia.between_refine_m, ib.between_refine_m);
  EXPECT_EQ(ia.between_refine_rad, ib.between_refine_rad);
}

/// Field-by-field equality of two configs (exact: the file format must round-trip doubles).
void ExpectSameConfig(const MapperConfig& a, const MapperConfig& b) {
  EXPECT_EQ(a.keyframes.min_translation_m, b.keyframes.min_translation_m);
  EXPECT_EQ(a.keyframes.min_rotation_rad, b.keyframes.min_rotation_rad);
  ExpectSameIncremental(a.incremental, b.incremental);
  ExpectSameLoops(a.loops, b.loops);
  EXPECT_EQ(a.pruning.mode.name, b.pruning.mode.name);
  EXPECT_EQ(a.pruning.gain_threshold_bits, b.pruning.gain_threshold_bits);
  EXPECT_EQ(a.pruning.radius_m, b.pruning.radius_m);
  EXPECT_EQ(a.pruning.keep_recent_nodes, b.pruning.keep_recent_nodes);
  EXPECT_EQ(a.pruning.round_period, b.pruning.round_period);
  EXPECT_EQ(a.pruning.node_budget, b.pruning.node_budget);
  EXPECT_EQ(a.pruning.max_edges_per_node, b.pruning.max_edges_per_node);
  EXPECT_EQ(a.pruning.blanket, b.pruning.blanket);
  EXPECT_EQ(a.pruning.nfr_chords, b.pruning.nfr_chords);
  EXPECT_EQ(a.pruning.nfr_chord_ratio, b.pruning.nfr_chord_ratio);
  EXPECT_EQ(a.pruning.factor_means, b.pruning.factor_means);
  EXPECT_EQ(a.pruning.robust_marginal, b.pruning.robust_marginal);
  EXPECT_EQ(a.pruning.overlap.iou_min, b.pruning.overlap.iou_min);
  EXPECT_EQ(a.pruning.overlap.iou_match, b.pruning.overlap.iou_match);
  EXPECT_EQ(a.pruning.overlap.removal_score, b.pruning.overlap.removal_score);
  EXPECT_EQ(a.pruning.overlap.overlap_scale, b.pruning.overlap.overlap_scale);
  EXPECT_EQ(a.pruning.overlap.constraint_scale, b.pruning.overlap.constraint_scale);
  EXPECT_EQ(a.pruning.overlap.nearby_penalty, b.pruning.overlap.nearby_penalty);
  EXPECT_EQ(a.pruning.overlap.scan_buffer, b.pruning.overlap.scan_buffer);
  EXPECT_EQ(a.pruning.dpg.detection.margin_m, b.pruning.dpg.detection.margin_m);
  EXPECT_EQ(a.pruning.dpg.detection.edge_guard_m, b.pruning.dpg.detection.edge_guard_m);
  EXPECT_EQ(a.pruning.dpg.detection.min_agreement, b.pruning.dpg.detection.min_agreement);
  EXPECT_EQ(a.pruning.dpg.detection.min_incidence_rad, b.pruning.dpg.detection.min_incidence_rad);
  EXPECT_EQ(a.pruning.dpg.detection.min_incidence_added_rad,
            b.pruning.dpg.detection.min_incidence_added_rad);
  EXPECT_EQ(a.pruning.dpg.detection.added_depth_m, b.pruning.dpg.detection.added_depth_m);
  EXPECT_EQ(a.pruning.dpg.detection.min_run_beams, b.pruning.dpg.detection.min_run_beams);
  EXPECT_EQ(a.pruning.dpg.detection.min_run_occluded_beams,
            b.pruning.dpg.detection.min_run_occluded_beams);
  EXPECT_EQ(a.pruning.dpg.min_active_share, b.pruning.dpg.min_active_share);
  EXPECT_EQ(a.pruning.dpg.compare_radius_m, b.pruning.dpg.compare_radius_m);
  EXPECT_EQ(a.pruning.dpg.min_agreement_vouched, b.pruning.dpg.min_agreement_vouched);
  EXPECT_EQ(a.grid.resolution_m, b.grid.resolution_m);
  EXPECT_EQ(a.grid.max_free_range_m, b.grid.max_free_range_m);
  EXPECT_EQ(a.grid.max_hit_range_m, b.grid.max_hit_range_m);
  EXPECT_EQ(a.grid.max_dropout_beams, b.grid.max_dropout_beams);
  EXPECT_EQ(a.grid.hits_mask_own_misses, b.grid.hits_mask_own_misses);
  EXPECT_EQ(a.grid.present_timescale_s, b.grid.present_timescale_s);
  EXPECT_EQ(a.grid.present_shape, b.grid.present_shape);
  ExpectSameOptimizer(a.optimizer, b.optimizer);
  EXPECT_EQ(a.map_move_epsilon_m, b.map_move_epsilon_m);
  EXPECT_EQ(a.map_move_epsilon_rad, b.map_move_epsilon_rad);
}

void ChangeMatcher(slam::MatcherConfig* m, bool windows) {
  if (windows) {
    m->linear_window_m = 0.7;
    m->angular_window_rad = 0.1 / 3.0;  // not a short decimal: tests exact round trip
  }
  m->resolution_m = 0.02;
  m->angular_step_rad = 0.011;
  m->coarse_factor = 8;
  m->sigma_m = 0.07;
  m->min_score = 0.45;
  m->ambiguity_radius_m = 0.9;
  m->ambiguity_angle_rad = 0.3;
  m->floor_sigma_m = 0.02;
  m->floor_sigma_rad = 0.004;
  m->refine = !m->refine;
}

/// A valid config that differs from the defaults in every setting the file holds (data table).
MapperConfig AllChanged() {
  MapperConfig c;
  c.keyframes = {0.25, 0.2};
  c.incremental.local_map_nodes = 5;
  c.incremental.point_spacing_m = 0.04;
  c.incremental.surfaces = {0.25, 2.5, 0.03};
  ChangeMatcher(&c.incremental.matcher, true);
  c.incremental.odom_sigma_xy_m = 0.06;
  c.incremental.odom_sigma_xy_per_m = 0.2;
  c.incremental.odom_sigma_rad = 0.03;
  c.incremental.odom_sigma_rad_per_rad = 0.15;
  c.incremental.max_ambiguity = 0.8;
  c.incremental.weak_score = 0.45;
  c.incremental.weak_max_ambiguity = 0.65;
  c.incremental.lost_window_m = 1.5;
  c.incremental.recovery_window_m = 2.5;
  c.incremental.recover_past_odometry = false;
  c.incremental.between_refine_m = 0.15;
  c.incremental.between_refine_rad = 0.07;
  slam::LoopClosingConfig& l = c.loops;
  l.enabled = false;
  l.min_path_separation_m = 4.0;
  l.overlap_radius_m = 1.5;
  l.gate_chi2 = 9.21;
  l.max_position_sigma_m = 3.0;
  l.min_window_m = 0.4;
  l.max_window_m = 1.5;
  l.min_window_rad = 0.1;
  l.max_window_rad = 0.6;
  l.neighbours_per_candidate = 1;
  l.submap_span = 7;
  l.max_flatness = 0.8;
  l.uniqueness_radius_m = 0.4;
  l.context_ambiguity = 0.55;
  l.context_span_m = 12.0;
  l.refine_window_m = 0.2;
  l.refine_window_rad = 0.07;
  l.min_score = 0.7;
  l.max_ambiguity = 0.9;
  l.consistency_chi2 = 11.34;
  l.min_reference_points = 40;
  l.surfaces = false;
  l.surface_lines = false;
  l.measure_low_scores = true;
  ChangeMatcher(&l.matcher, false);  // its windows are set per attempt, not in the file
  l.optimize_edge_chi2 = 4.0;
  l.optimize_every = 3;
  l.verify = {false, 2, 9.0, 30.0, 20.0, 0.004, 0.002, 0.0005, 0.0001};
  l.global = {false, 3,   15.0, 2,   30,  0.3,           20, 8, 0.5, 3, 3.0,
              0.3,   7.0, 9.0,  4.0, 2.5, {15, 72, 25.0}};
  l.suspect_chi2 = 12.0;
  c.pruning = {slam::NamedMode("standard"),
               -0.5,
               4.5,
               2,
               4,
               300,
               1.5,
               slam::BlanketPolicy::kFactorsAtK,
               slam::NfrChords::kMutualInformation,
               0.5,
               slam::FactorMeans::kMarginalMean,
               true,
               {0.2, 0.8, 0.2, 0.4, 0.1, 0.01, 5},
               {{0.25, 0.15, 0.3, 0.2, 0.6, 5, 3, 0.7}, 0.4, 8.0, 0.3}};
  c.grid = {0.1, 6.0, 9.5, 3, false};
  slam::OptimizerParams& o = c.optimizer;
  o.method = slam::OptimizerMethod::kGaussNewton;
  o.max_iterations = 25;
  o.relative_tolerance = 2e-6;
  o.step_tolerance = 3e-9;
  o.absolute_tolerance = 1e-12;
  o.robust_kernel = slam::RobustKernel::kHuber;
  o.robust_delta = 1.5;
  o.scale_damping = false;
  o.initial_lambda_factor = 1e-3;
  o.evaluate_final_chi2 = false;
  o.linear_initialization = true;
  o.linear_solver = slam::LinearSolver::kSupernodal;
  c.map_move_epsilon_m = 0.02;
  c.map_move_epsilon_rad = 0.01;
  return c;
}

const std::string kDir = std::string(LIFELONG_SOURCE_DIR) + "/configs/";

TEST(MapperConfigFile, DefaultYamlSetsEveryKeyToTheCodeDefaults) {
  // Loaded on top of a config where everything differs, so a key missing from the file or a
  // value that drifted from MapperConfig{} both show.
  ExpectSameConfig(LoadMapperConfig(kDir + "default.yaml", AllChanged()), slam::MapperConfig{});
}

// The false-closure test is eval's section, beside the mapper's: default.yaml gives it off,
// a file sets it with the same checks, and a sweep's dotted settings reach it.
TEST(MapperConfigFile, TheFalseClosureSectionIsReadBesideTheMappersSettings) {
  const FalseClosureConfig defaults = LoadFalseClosureConfig(kDir + "default.yaml");
  const FalseClosureConfig off;
  EXPECT_EQ(defaults.share, off.share);
  EXPECT_EQ(defaults.dx_m, off.dx_m);
  EXPECT_EQ(defaults.dy_m, off.dy_m);
  const FalseClosureConfig set = FalseClosureConfigFromString(
      "loops:\n  min_score: 0.7\nfalse_closures:\n  share: 0.05\n  dy_m: 3.8\n", "test.yaml");
  EXPECT_EQ(set.share, 0.05);
  EXPECT_EQ(set.dx_m, 0.0);
  EXPECT_EQ(set.dy_m, 3.8);
  EXPECT_THROW(FalseClosureConfigFromString("false_closures:\n  share: 2\n", "t.yaml"), InputError);
  EXPECT_THROW(FalseClosureConfigFromString("loops:\n  inject_false_share: 0.05\n", "t.yaml"),
               InputError);  // the mapper has no such key any more
  EXPECT_EQ(MapperSettingsYaml({{"false_closures.share", "0.05"}}),
            "false_closures:\n  share: 0.05\n");
  EXPECT_NO_THROW(ApplyMapperSettings({{"false_closures.share", "0.05"}}, "setting"));
}

TEST(MapperConfigFile, PrunedBudgetExampleSetsOnlyThePruning) {
  MapperConfig expected;
  expected.pruning.radius_m = 8.0;
  expected.pruning.node_budget = 150;
  ExpectSameConfig(LoadMapperConfig(kDir + "pruned_budget.yaml"), expected);
}

TEST(MapperConfigFile, SeedMarginalizationExampleRestoresTheSeedsRules) {
  const MapperConfig loaded = LoadMapperConfig(kDir + "seed_marginalization.yaml");
  MapperConfig expected;
  expected.pruning.gain_threshold_bits = 0.0;
  expected.pruning.max_edges_per_node = 0.0;
  expected.pruning.factor_means = slam::FactorMeans::kEstimate;
  expected.pruning.robust_marginal = false;
  ExpectSameConfig(loaded, expected);
}

TEST(MapperConfigFile, DenseKeyframesExampleSetsOnlyTheKeyframes) {
  MapperConfig expected;
  expected.keyframes = {0.25, 0.2};
  ExpectSameConfig(LoadMapperConfig(kDir + "dense_keyframes.yaml"), expected);
}

TEST(MapperConfigFile, OverridesApplyAndTheRestStaysAtBase) {
  MapperConfig base = AllChanged();
  base.pruning.mode = slam::NamedMode("pruned");
  const MapperConfig loaded = LoadMapperConfigFromString(
      "pruning: {node_budget: 50, radius_m: 6.5}\n"
      "loops:\n  matcher:\n    sigma_m: 0.1\n",
      "test.yaml", base);
  MapperConfig expected = base;
  expected.pruning.node_budget = 50;
  expected.pruning.radius_m = 6.5;
  expected.loops.matcher.sigma_m = 0.1;
  ExpectSameConfig(loaded, expected);
}

TEST(MapperConfigFile, EmptyDocumentsAndSectionsGiveTheBase) {
  const MapperConfig base = AllChanged();
  ExpectSameConfig(LoadMapperConfigFromString("", "empty.yaml", base), base);
  ExpectSameConfig(LoadMapperConfigFromString("# nothing\npruning:\n", "c.yaml", base), base);
}

TEST(MapperConfigFile, EnumsAreReadByName) {
  const MapperConfig c = LoadMapperConfigFromString(
      "optimizer: {method: gn, robust_kernel: none, linear_solver: simplicial}\n", "e.yaml");
  EXPECT_EQ(c.optimizer.method, slam::OptimizerMethod::kGaussNewton);
  EXPECT_EQ(c.optimizer.robust_kernel, slam::RobustKernel::kNone);
  EXPECT_EQ(c.optimizer.linear_solver, slam::LinearSolver::kSimplicial);
  const MapperConfig d = LoadMapperConfigFromString(
      "optimizer: {method: lm, robust_kernel: huber, linear_solver: supernodal}\n", "e.yaml", c);
  EXPECT_EQ(d.optimizer.method, slam::OptimizerMethod::kLevenbergMarquardt);
  EXPECT_EQ(d.optimizer.robust_kernel, slam::RobustKernel::kHuber);
  EXPECT_EQ(d.optimizer.linear_solver, slam::LinearSolver::kSupernodal);
}

TEST(MapperConfigFile, RoundTripsTheDefaultsAndAChangedConfig) {
  const std::string defaults = MapperConfigToYaml(slam::MapperConfig{});
  ExpectSameConfig(LoadMapperConfigFromString(defaults, "rt", AllChanged()), slam::MapperConfig{});
  const MapperConfig changed = AllChanged();
  ExpectSameConfig(LoadMapperConfigFromString(MapperConfigToYaml(changed), "rt"), changed);
  // A run's config.yaml keeps its false-closure test too.
  const FalseClosureConfig injected{0.05, -1.0, 3.8};
  const FalseClosureConfig back =
      FalseClosureConfigFromString(MapperConfigToYaml(changed, injected), "rt");
  EXPECT_EQ(back.share, 0.05);
  EXPECT_EQ(back.dx_m, -1.0);
  EXPECT_EQ(back.dy_m, 3.8);
}

}  // namespace
}  // namespace lifelong::eval
