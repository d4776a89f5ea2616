// Sparse least-squares back-end for the pose graph: Levenberg-Marquardt (or plain
// Gauss-Newton) over all nodes, one node anchored, the normal equations factorized with
// CHOLMOD. Seed §2.3 (graph-based SLAM as least squares, F(x) = sum e_ij^T Omega_ij e_ij);
// the damping follows Nielsen (1999) / Madsen et al. "Methods for non-linear least squares"
// §3.2: solve (H + lambda D) dx = -g, accept when the gain ratio is positive.
//
// Steps per call:
//  1. map NodeId -> column block once (anchor and factor-less nodes get no columns);
//  2. build the upper-triangular block pattern of H in CSC form once, analyze it once
//     (fill-reducing ordering, symbolic factorization) and reuse it every iteration;
//  2b. optionally (default) a linear initialization: headings, then positions, by two
//     linear least-squares solves (Carlone et al. 2014, LAGO), kept if chi2 drops;
//  3. per iteration: linearize every factor (se2.hpp's analytic Jacobians), scatter the
//     3x3 blocks straight into the CSC value array, factorize numerically, solve, update
//     x <- x + dx additively with the angle normalized, evaluate chi2, accept or reject.
//
// Robust kernels (IRLS) act on edges with `robust = true`: with s = e^T Omega e,
//   Huber:  rho(s) = s                    (s <= d^2),  2 d sqrt(s) - d^2  otherwise
//   Cauchy: rho(s) = d^2 log(1 + s / d^2)
//   DCS:    rho(s) = s (s <= Phi),  Phi (3 s - Phi) / (s + Phi) otherwise, Phi = d^2
// and the edge is weighted by rho'(s). DCS is dynamic covariance scaling (Agarwal, Tipaldi,
// Spinello, Stachniss & Burgard, ICRA 2013): its weight rho'(s) = min(1, 2 Phi/(Phi + s))^2
// is the paper's scaling factor squared (eq. 15 applied to Omega), the closed form of a
// switchable constraint's optimal switch (Suenderhauf & Protzel 2012) with prior Phi, so a
// closure that disagrees with the rest is switched off (weight ~ 4 Phi^2 / s^2), not just
// down-weighted as by Cauchy (~ d^2 / s). The reported chi2 is the robust cost sum rho(s)
// (identical to sum e^T Omega e when no robust edge is active).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "slam/graph/pose_graph.hpp"

namespace lifelong::slam {

enum class RobustKernel : std::uint8_t { kNone, kHuber, kCauchy, kDcs };
enum class OptimizerMethod : std::uint8_t { kLevenbergMarquardt, kGaussNewton };
enum class LinearSolver : std::uint8_t { kAuto, kSimplicial, kSupernodal };

struct OptimizerParams {
  OptimizerMethod method = OptimizerMethod::kLevenbergMarquardt;
  /// Maximum number of linear solves (each LM trial step counts, accepted or not).
  int max_iterations = 100;
  /// Stop when an accepted step lowers chi2 by less than this fraction of chi2.
  double relative_tolerance = 1e-9;
  /// Stop when the largest increment component is below this (m and rad).
  double step_tolerance = 1e-10;
  /// Stop when chi2 itself is below this (a perfectly consistent graph).
  double absolute_tolerance = 1e-18;
  /// The node held fixed (gauge); default: the smallest node id.
  std::optional<NodeId> anchor;
  RobustKernel robust_kernel = RobustKernel::kNone;
  /// Kernel width d, in units of Mahalanobis distance sqrt(e^T Omega e) (dimensionless).
  double robust_delta = 1.0;
  /// LM damping matrix: lambda * diag(H) (Marquardt's scaling, invariant to the units of
  /// x, y and theta) when true; lambda * I (as g2o) when false.
  bool scale_damping = true;
  /// Initial LM damping: lambda_0 = factor (scaled damping) or factor * max diag(H).
  double initial_lambda_factor = 1e-5;
  /// Gauss-Newton only: spend one extra error pass at the end so that final_chi2 is the
  /// chi2 of the returned values. When false, final_chi2 is the chi2 at the last
  /// linearization point (before the last step), and no extra pass is made.
  bool evaluate_final_chi2 = true;
  /// Before iterating, re-estimate all headings and then all positions by two linear
  /// least-squares solves (LAGO-style, see optimizer.cpp) and keep the result only if it
  /// lowers the objective. Skipped when the graph has clique factors or robust edges with
  /// an active kernel (a least-squares guess would let outliers pull the start).
  bool linear_initialization = true;
  /// CHOLMOD's factorization: chosen by density (kAuto), or forced.
  LinearSolver linear_solver = LinearSolver::kAuto;
};

struct OptimizerSummary {
  double initial_chi2 = 0.0;  ///< robust cost at the warm start (see header comment)
  double final_chi2 = 0.0;    ///< robust cost at the returned values
  int iterations = 0;         ///< linear solves performed
  double solve_time_s = 0.0;  ///< wall time of the whole Optimize call
  bool converged = false;     ///< a tolerance was met (not just max_iterations)
  std::string message;        ///< which stopping rule fired
  int accepted_steps = 0;
  int rejected_steps = 0;          ///< LM steps that raised chi2
  int factorization_failures = 0;  ///< non-SPD systems met (damping was raised)
  double final_lambda = 0.0;       ///< LM damping at exit
  /// Objective after the linear initialization (infinity if its solve failed; 0 if not run).
  double initialization_chi2 = 0.0;
  bool initialization_used = false;  ///< it lowered chi2 and the iterations started there
};

/// Optimizes `values` in place, warm-started from them. Every node of `graph` must have a
/// value (std::invalid_argument otherwise); extra entries in `values` are left untouched.
OptimizerSummary Optimize(const PoseGraph& graph, Values* values,
                          const OptimizerParams& params = {});

/// "lm" -> kLevenbergMarquardt, "gn" -> kGaussNewton; false (and *method untouched) for
/// any other name.
bool ParseOptimizerMethod(const std::string& name, OptimizerMethod* method);

/// The objective at `values`: sum of e^T Omega e over edges and clique factors, robust
/// edges through params' kernel.
double ComputeChi2(const PoseGraph& graph, const Values& values,
                   const OptimizerParams& params = {});

}  // namespace lifelong::slam
