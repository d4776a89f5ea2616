#include "apps/optimize_command.hpp"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "io/graph_file.hpp"
#include "sensor/input_error.hpp"
#include "slam/backend/optimizer.hpp"

namespace lifelong::apps {

int OptimizeGraph(const OptimizeArgs& args) {
  slam::OptimizerParams params;
  if (!slam::ParseOptimizerMethod(args.method, &params.method)) {
    throw InputError("--method", 0, args.method, "unknown method (known: lm, gn)");
  }
  if (args.solver == "simplicial") {
    params.linear_solver = slam::LinearSolver::kSimplicial;
  } else if (args.solver == "supernodal") {
    params.linear_solver = slam::LinearSolver::kSupernodal;
  } else if (args.solver != "auto") {
    throw InputError("--solver", 0, args.solver,
                     "unknown solver (known: auto, simplicial, supernodal)");
  }
  params.linear_initialization = !args.no_init;
  io::GraphFile file = io::ReadGraphFile(args.graph);
  const slam::PoseGraph graph = slam::PoseGraph::FromFactors(file.factors);
  if (graph.NumNodes() == 0) throw InputError(args.graph, 0, "", "the graph has no vertices");
  const auto summary = slam::Optimize(graph, &file.values, params);
  if (!std::isfinite(summary.initial_chi2) || !std::isfinite(summary.final_chi2)) {
    std::ostringstream what;
    what << "the graph's chi2 is not finite (initial " << summary.initial_chi2 << ", final "
         << summary.final_chi2 << "): its measurements or information overflow";
    throw InputError(args.graph, 0, "", what.str());
  }
  std::cout << std::setprecision(10) << "vertices " << graph.NumNodes() << "\nedges "
            << graph.edges().size() << "\ninitial_chi2 " << summary.initial_chi2 << "\nfinal_chi2 "
            << summary.final_chi2 << "\niterations " << summary.iterations << "\nsolve_time_s "
            << summary.solve_time_s << "\nconverged " << (summary.converged ? "yes" : "no") << " ("
            << summary.message << ")\n";
  if (!args.out.empty()) io::WriteG2o(args.out, graph.Factors(), file.values);
  return 0;
}

}  // namespace lifelong::apps
