// The drivers of the back-end (slam/backend/optimizer.hpp): Levenberg-Marquardt and Gauss-Newton
// iterations and their stopping rules. The parts they drive, one job each:
//   optimizer_problem   layout of the unknowns, objective (robust kernels, chi2), updates;
//   optimizer_cholmod   the sparse Cholesky (CHOLMOD) of the normal equations;
//   optimizer_system    linearization: H and g from the factors' Jacobians;
//   optimizer_lago      the linear initialization (LAGO).
#include "slam/backend/optimizer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

#include "slam/backend/optimizer_cholmod.hpp"
#include "slam/backend/optimizer_lago.hpp"
#include "slam/backend/optimizer_problem.hpp"
#include "slam/backend/optimizer_system.hpp"

namespace lifelong::slam {
namespace {

using backend::ApplyStep;
using backend::BuildLayout;
using backend::Chi2;
using backend::Cholmod;
using backend::EdgeSlot;
using backend::InitializeHeadings;
using backend::InitializePositions;
using backend::Layout;
using backend::Restore;
using backend::Snapshot;
using backend::System;

bool Converged(double old_chi2, double new_chi2, const OptimizerParams& params,
               OptimizerSummary* summary) {
  if (new_chi2 < params.absolute_tolerance) {
    summary->message = "chi2 below absolute tolerance";
  } else if (std::abs(old_chi2 - new_chi2) < params.relative_tolerance * old_chi2) {
    summary->message = "relative chi2 decrease below tolerance";
  } else {
    return false;
  }
  summary->converged = true;
  return true;
}

bool StepTiny(const Eigen::VectorXd& dx, const OptimizerParams& params, OptimizerSummary* summary) {
  if (dx.size() > 0 && dx.lpNorm<Eigen::Infinity>() >= params.step_tolerance) return false;
  summary->converged = true;
  summary->message = "step below tolerance";
  return true;
}

// Levenberg-Marquardt with Nielsen's damping update.
void RunLevenbergMarquardt(const Layout& layout, Cholmod* solver, System* system,
                           const OptimizerParams& params, double chi2, OptimizerSummary* summary) {
  const bool marquardt = params.scale_damping;
  Eigen::VectorXd D = system->DampingScale(marquardt);
  // lambda_0 = tau (Marquardt) or tau * max diag(H) (Nielsen / g2o; D is all ones there).
  double lambda = params.initial_lambda_factor * (marquardt ? 1.0 : system->MaxDiagonal());
  lambda = std::max(lambda, 1e-300);
  double nu = 2.0;
  Eigen::VectorXd dx;
  summary->message = "maximum iterations reached";
  while (summary->iterations < params.max_iterations) {
    ++summary->iterations;
    if (!solver->Solve(system->H(), lambda, D, -system->g(), &dx)) {
      ++summary->factorization_failures;
      lambda *= nu;
      nu *= 2.0;
      continue;
    }
    if (StepTiny(dx, params, summary)) break;
    const std::vector<Pose2> saved = Snapshot(layout);
    ApplyStep(layout, dx);
    const double new_chi2 = Chi2(layout, params);
    const double predicted = dx.dot(lambda * D.cwiseProduct(dx) - system->g());
    const double rho = (chi2 - new_chi2) / predicted;
    if (std::isfinite(new_chi2) && new_chi2 < chi2 && predicted > 0.0) {
      ++summary->accepted_steps;
      const double old_chi2 = chi2;
      chi2 = new_chi2;
      lambda *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
      nu = 2.0;
      if (Converged(old_chi2, chi2, params, summary)) break;
      system->Linearize(params);
      D = system->DampingScale(marquardt);
    } else {
      Restore(layout, saved);
      ++summary->rejected_steps;
      lambda *= nu;
      nu *= 2.0;
      if (lambda > 1e40) {
        summary->message = "damping exhausted: no further decrease";
        summary->converged = true;
        break;
      }
    }
  }
  summary->final_chi2 = chi2;
  summary->final_lambda = lambda;
}

// Gauss-Newton: no trial evaluations; chi2 comes with each linearization. A non-SPD system
// gets a small damping that grows until the factorization succeeds.
void RunGaussNewton(const Layout& layout, Cholmod* solver, System* system,
                    const OptimizerParams& params, double chi2, OptimizerSummary* summary) {
  bool stale = false;  // values moved since the last chi2
  const Eigen::VectorXd ones = system->DampingScale(false);
  Eigen::VectorXd dx;
  summary->message = "maximum iterations reached";
  while (summary->iterations < params.max_iterations) {
    ++summary->iterations;
    double lambda = 0.0;
    while (!solver->Solve(system->H(), lambda, ones, -system->g(), &dx)) {
      ++summary->factorization_failures;
      lambda = lambda == 0.0 ? 1e-9 * std::max(system->MaxDiagonal(), 1e-12) : 10.0 * lambda;
      if (lambda > 1e40) break;
    }
    summary->final_lambda = lambda;
    if (lambda > 1e40) {
      summary->message = "factorization failed";
      break;
    }
    if (StepTiny(dx, params, summary)) break;
    ApplyStep(layout, dx);
    ++summary->accepted_steps;
    if (summary->iterations == params.max_iterations) {
      stale = true;  // skip the linearization nobody would use
      break;
    }
    const double new_chi2 = system->Linearize(params);
    if (Converged(chi2, new_chi2, params, summary)) {
      chi2 = new_chi2;
      break;
    }
    chi2 = new_chi2;
  }
  if (stale && params.evaluate_final_chi2) chi2 = Chi2(layout, params);
  summary->final_chi2 = chi2;
}

bool AnyRobustEdge(const Layout& layout, const OptimizerParams& params) {
  if (params.robust_kernel == RobustKernel::kNone) return false;
  return std::any_of(layout.edges.begin(), layout.edges.end(),
                     [](const EdgeSlot& s) { return s.edge->robust; });
}

// Runs the linear initialization and keeps it only if it lowers the objective.
void MaybeInitialize(const Layout& layout, const OptimizerParams& params,
                     OptimizerSummary* summary) {
  const std::vector<Pose2> saved = Snapshot(layout);
  const bool solved = InitializeHeadings(layout) && InitializePositions(layout);
  const double chi2 = solved ? Chi2(layout, params) : std::numeric_limits<double>::infinity();
  summary->initialization_chi2 = chi2;
  summary->initialization_used = std::isfinite(chi2) && chi2 < summary->initial_chi2;
  if (!summary->initialization_used) Restore(layout, saved);
}

NodeId ChooseAnchor(const PoseGraph& graph, const OptimizerParams& params) {
  if (params.anchor) {
    if (!graph.HasNode(*params.anchor)) {
      throw std::invalid_argument("Optimize: anchor node is not in the graph");
    }
    return *params.anchor;
  }
  return graph.NodeIds().front();
}

}  // namespace

OptimizerSummary Optimize(const PoseGraph& graph, Values* values, const OptimizerParams& params) {
  const auto start = std::chrono::steady_clock::now();
  OptimizerSummary summary;
  if (graph.NumNodes() == 0) {
    summary.converged = true;
    summary.message = "empty graph";
    return summary;
  }
  const Layout layout = BuildLayout(graph, values, ChooseAnchor(graph, params));
  Cholmod solver(layout, params.linear_solver);
  System system(layout, solver.ColPtr(), solver.Nnz());
  summary.initial_chi2 = Chi2(layout, params);
  if (params.linear_initialization && layout.num_blocks > 0 && layout.cliques.empty() &&
      !AnyRobustEdge(layout, params)) {
    MaybeInitialize(layout, params, &summary);
  }
  const double start_chi2 = system.Linearize(params);
  summary.final_chi2 = start_chi2;
  if (!std::isfinite(start_chi2)) {
    // Nothing can be decreased from here; the values are left as they came.
    summary.message = "chi2 is not finite at the start (measurements or information overflow)";
  } else if (layout.num_blocks == 0 || start_chi2 < params.absolute_tolerance) {
    summary.converged = true;
    summary.message =
        layout.num_blocks == 0 ? "nothing to optimize" : "chi2 below absolute tolerance";
  } else if (params.method == OptimizerMethod::kGaussNewton) {
    RunGaussNewton(layout, &solver, &system, params, start_chi2, &summary);
  } else {
    RunLevenbergMarquardt(layout, &solver, &system, params, start_chi2, &summary);
  }
  summary.solve_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

bool ParseOptimizerMethod(const std::string& name, OptimizerMethod* method) {
  if (name == "lm") {
    *method = OptimizerMethod::kLevenbergMarquardt;
  } else if (name == "gn") {
    *method = OptimizerMethod::kGaussNewton;
  } else {
    return false;
  }
  return true;
}

double ComputeChi2(const PoseGraph& graph, const Values& values, const OptimizerParams& params) {
  if (graph.NumNodes() == 0) return 0.0;
  Values copy = values;  // the layout holds mutable pointers; the copy keeps `values` const
  const Layout layout = BuildLayout(graph, &copy, graph.NodeIds().front());
  return Chi2(layout, params);
}

}  // namespace lifelong::slam
