// Back-end benchmark on the public pose graphs in ../shared/datasets/pose_graphs.
//
// BM_Optimize/<graph>: slam::Optimize (LM, CHOLMOD) from the file's initial guess (or the
//   chained odometry for edges-only files); counters: nodes, edges, initial/final chi2,
//   iterations.
// BM_OptimizeGaussNewton/<graph>: the same with params.method = kGaussNewton.
// BM_OptimizeNoInit/<graph>: LM with params.linear_initialization = false (the LM before
//   the initialization was added; shows what the initialization buys).
// BM_OptimizeWarm/<graph>: LM warm-started at the optimum (per-call overhead).
// BM_Reference/<graph>: an independent check of the optimum's chi2 that shares no code
//   with the optimizer beyond Pose2: right-multiplicative increments X <- X * Exp(d),
//   residuals whitened by the Cholesky factor of Omega, central-difference numerical
//   Jacobians, J assembled as a sparse matrix and J^T J formed by Eigen's sparse product,
//   solved with Eigen::SimplicialLDLT, Gauss-Newton with step halving, relative tolerance
//   1e-12. It runs from the file's initial guess and again from the optimizer's result
//   (which it must not be able to improve).
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>
#include <Eigen/Cholesky>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "io/graph_file.hpp"
#include "slam/backend/optimizer.hpp"

namespace lifelong {
namespace {

struct LoadedGraph {
  slam::PoseGraph graph;
  slam::Values values;  ///< the file's initial guess
};

const LoadedGraph* Load(const std::string& name) {
  static std::map<std::string, LoadedGraph> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return &it->second;
  const std::string path = std::string(LIFELONG_SHARED_DIR) + "/datasets/pose_graphs/" + name;
  try {
    io::GraphFile file = io::ReadGraphFile(path);
    LoadedGraph loaded{slam::PoseGraph::FromFactors(file.factors), std::move(file.values)};
    return &cache.emplace(name, std::move(loaded)).first->second;
  } catch (const std::exception&) {
    return nullptr;
  }
}

// ---- independent reference: Gauss-Newton on whitened residuals, numerical Jacobians ----
struct RefEdge {
  int i, j;
  Pose2 Z_inv;
  Eigen::Matrix3d L_T;  // Omega = L L^T, whitened residual r = L^T e
};

Eigen::Vector3d RefResidual(const RefEdge& e, const Pose2& Xi, const Pose2& Xj) {
  const Pose2 d = e.Z_inv * (Xi.Inverse() * Xj);
  return e.L_T * Eigen::Vector3d(d.x, d.y, d.theta);
}

Pose2 Retract(const Pose2& X, const Eigen::Vector3d& d) {  // X * Exp(d), SE(2) exponential
  const double th = d.z();
  const double a = std::abs(th) < 1e-9 ? 1.0 : std::sin(th) / th;
  const double b = std::abs(th) < 1e-9 ? 0.0 : (1.0 - std::cos(th)) / th;
  return X * Pose2(a * d.x() - b * d.y(), b * d.x() + a * d.y(), th);
}

double RefCost(const std::vector<RefEdge>& edges, const std::vector<Pose2>& x) {
  double c = 0.0;
  for (const RefEdge& e : edges) {
    c += RefResidual(e, x[static_cast<std::size_t>(e.i)], x[static_cast<std::size_t>(e.j)])
             .squaredNorm();
  }
  return c;
}

Eigen::SparseMatrix<double> RefJacobian(const std::vector<RefEdge>& edges,
                                        const std::vector<Pose2>& x, Eigen::VectorXd* r) {
  const double h = 1e-7;
  std::vector<Eigen::Triplet<double>> t;
  r->resize(3 * static_cast<Eigen::Index>(edges.size()));
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const RefEdge& e = edges[k];
    const Pose2 &Xi = x[static_cast<std::size_t>(e.i)], &Xj = x[static_cast<std::size_t>(e.j)];
    const int row = 3 * static_cast<int>(k);
    r->segment<3>(row) = RefResidual(e, Xi, Xj);
    for (int c = 0; c < 3; ++c) {
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      d[c] = h;
      Eigen::Vector3d di = RefResidual(e, Retract(Xi, d), Xj) - RefResidual(e, Retract(Xi, -d), Xj);
      Eigen::Vector3d dj = RefResidual(e, Xi, Retract(Xj, d)) - RefResidual(e, Xi, Retract(Xj, -d));
      for (int q = 0; q < 3; ++q) {  // column 3 * node + c; node 0 (the anchor) is dropped
        if (e.i > 0) t.emplace_back(row + q, 3 * (e.i - 1) + c, di[q] / (2 * h));
        if (e.j > 0) t.emplace_back(row + q, 3 * (e.j - 1) + c, dj[q] / (2 * h));
      }
    }
  }
  Eigen::SparseMatrix<double> J(r->size(), 3 * (static_cast<Eigen::Index>(x.size()) - 1));
  J.setFromTriplets(t.begin(), t.end());
  return J;
}

// Dense node indices (ascending ids, index 0 = the anchor) and whitened edges.
std::vector<RefEdge> RefEdges(const slam::PoseGraph& g, std::map<slam::NodeId, int>* index) {
  int n = 0;
  for (slam::NodeId id : g.NodeIds()) (*index)[id] = n++;
  std::vector<RefEdge> out;
  for (const slam::PoseEdge& e : g.edges()) {
    const Eigen::Matrix3d L = e.information.llt().matrixL();
    out.push_back({index->at(e.from), index->at(e.to), e.T_from_to.Inverse(), L.transpose()});
  }
  return out;
}

struct RefResult {
  double chi2;
  int iterations;
};

RefResult ReferenceSolve(const std::vector<RefEdge>& edges, std::vector<Pose2>* x) {
  double cost = RefCost(edges, *x);
  int it = 0;
  for (; it < 200; ++it) {
    Eigen::VectorXd r;
    const Eigen::SparseMatrix<double> J = RefJacobian(edges, *x, &r);
    const Eigen::SparseMatrix<double> H = J.transpose() * J;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(H);
    const Eigen::VectorXd d = ldlt.solve(-(J.transpose() * r));
    double step = 1.0, new_cost = cost;
    std::vector<Pose2> trial;
    for (int halvings = 0; halvings < 30; ++halvings, step *= 0.5) {
      trial = *x;
      for (std::size_t k = 1; k < x->size(); ++k) {
        trial[k] = Retract((*x)[k], step * d.segment<3>(3 * static_cast<Eigen::Index>(k - 1)));
      }
      new_cost = RefCost(edges, trial);
      if (new_cost <= cost) break;
    }
    if (!(new_cost <= cost)) break;
    *x = trial;
    const bool done = cost - new_cost <= 1e-12 * cost;
    cost = new_cost;
    if (done) break;
  }
  return {cost, it};
}

void RunOptimize(benchmark::State& state, const std::string& name,
                 const slam::OptimizerParams& params, bool warm) {
  const LoadedGraph* f = Load(name);
  if (f == nullptr) return state.SkipWithError(("dataset absent: " + name).c_str());
  slam::Values start = f->values;
  if (warm) slam::Optimize(f->graph, &start, params);  // the mapper's case: already optimal
  slam::OptimizerSummary s;
  for (auto _ : state) {
    slam::Values values = start;
    s = slam::Optimize(f->graph, &values, params);
    benchmark::DoNotOptimize(values);
  }
  state.counters["nodes"] = static_cast<double>(f->graph.NumNodes());
  state.counters["edges"] = static_cast<double>(f->graph.edges().size());
  state.counters["chi2_initial"] = s.initial_chi2;
  state.counters["chi2_final"] = s.final_chi2;
  state.counters["iterations"] = s.iterations;
  state.counters["converged"] = s.converged ? 1 : 0;
  state.counters["init_used"] = s.initialization_used ? 1 : 0;
}

void BM_Optimize(benchmark::State& state, const std::string& name) {
  RunOptimize(state, name, slam::OptimizerParams{}, false);
}

void BM_OptimizeGaussNewton(benchmark::State& state, const std::string& name) {
  slam::OptimizerParams params;
  params.method = slam::OptimizerMethod::kGaussNewton;
  RunOptimize(state, name, params, false);
}

void BM_OptimizeNoInit(benchmark::State& state, const std::string& name) {
  slam::OptimizerParams params;
  params.linear_initialization = false;
  RunOptimize(state, name, params, false);
}

// Warm start at the optimum: the per-call overhead the mapper pays after a loop closure.
void BM_OptimizeWarm(benchmark::State& state, const std::string& name) {
  RunOptimize(state, name, slam::OptimizerParams{}, true);
}

void BM_Reference(benchmark::State& state, const std::string& name) {
  const LoadedGraph* f = Load(name);
  if (f == nullptr) return state.SkipWithError(("dataset absent: " + name).c_str());
  std::map<slam::NodeId, int> index;
  const std::vector<RefEdge> edges = RefEdges(f->graph, &index);
  RefResult from_file{}, from_lm{};
  for (auto _ : state) {
    std::vector<Pose2> x;
    for (const auto& [id, k] : index) x.push_back(f->values.at(id));
    from_file = ReferenceSolve(edges, &x);
  }
  slam::Values lm = f->values;
  slam::Optimize(f->graph, &lm);
  std::vector<Pose2> x;
  for (const auto& [id, k] : index) x.push_back(lm.at(id));
  const double lm_cost = RefCost(edges, x);
  from_lm = ReferenceSolve(edges, &x);
  state.counters["chi2_ref_from_file"] = from_file.chi2;
  state.counters["ref_iterations"] = from_file.iterations;
  state.counters["chi2_lm_by_ref"] = lm_cost;
  state.counters["chi2_ref_from_lm"] = from_lm.chi2;
}

BENCHMARK_CAPTURE(BM_Optimize, intel, std::string("intel.g2o"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Optimize, MIT, std::string("MIT.g2o"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Optimize, input_INTEL, std::string("input_INTEL_g2o.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Optimize, input_M3500, std::string("input_M3500_g2o.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Optimize, input_M3500b, std::string("input_M3500b_g2o.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Optimize, manhattan_chained, std::string("manhattan.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Optimize, city10000, std::string("city10000.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeGaussNewton, intel, std::string("intel.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeGaussNewton, MIT, std::string("MIT.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeGaussNewton, input_INTEL, std::string("input_INTEL_g2o.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeGaussNewton, input_M3500, std::string("input_M3500_g2o.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeGaussNewton, input_M3500b, std::string("input_M3500b_g2o.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeGaussNewton, manhattan_chained, std::string("manhattan.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeGaussNewton, city10000, std::string("city10000.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeNoInit, intel, std::string("intel.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeNoInit, MIT, std::string("MIT.g2o"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeNoInit, input_INTEL, std::string("input_INTEL_g2o.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeNoInit, input_M3500, std::string("input_M3500_g2o.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeNoInit, input_M3500b, std::string("input_M3500b_g2o.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeNoInit, manhattan_chained, std::string("manhattan.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeNoInit, city10000, std::string("city10000.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeWarm, intel, std::string("intel.g2o"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeWarm, input_M3500, std::string("input_M3500_g2o.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OptimizeWarm, city10000, std::string("city10000.g2o"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Reference, intel, std::string("intel.g2o"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_Reference, MIT, std::string("MIT.g2o"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_Reference, input_INTEL, std::string("input_INTEL_g2o.g2o"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_Reference, input_M3500, std::string("input_M3500_g2o.g2o"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_Reference, input_M3500b, std::string("input_M3500b_g2o.g2o"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_Reference, manhattan_chained, std::string("manhattan.g2o"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_Reference, city10000, std::string("city10000.g2o"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace
}  // namespace lifelong
