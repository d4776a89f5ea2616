// NFR at the clique level (nfr.hpp steps 1-2 and the topology): Sigma in the gauge of N[0],
// the Chow-Liu tree and the extra pairs, the factors' Jacobians, and the relative-pose edges.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "slam/graph/se2.hpp"
#include "slam/marginal/chow_liu.hpp"
#include "slam/marginal/marginalization.hpp"
#include "slam/sparsify/nfr.hpp"

namespace lifelong::slam {
namespace {

using Eigen::Index;
using Eigen::Matrix3d;
using Eigen::MatrixXd;

/// The diagonal shift chow-liu uses for a near-singular anchored information
/// (marginalization.cpp), relative to the mean diagonal.
constexpr double kRegularization = 1e-9;
/// An extra edge whose whitened information is below this (Frobenius) carries nothing.
constexpr double kZeroInformation = 1e-12;

/// Sigma = (Lambda_N with block 0 held)^-1, shifted when that is not definite.
MatrixXd AnchoredSigma(const MatrixXd& lambda_N, bool* regularized) {
  const Index d = lambda_N.rows() - 3;
  const MatrixXd a = lambda_N.bottomRightCorner(d, d);
  const MatrixXd id = MatrixXd::Identity(d, d);
  Eigen::LLT<MatrixXd> llt(a);
  if (llt.info() != Eigen::Success || !(llt.matrixLLT().diagonal().minCoeff() > 0.0)) {
    const double mean =
        std::max(a.trace() / static_cast<double>(d), std::numeric_limits<double>::min());
    llt.compute(a + kRegularization * mean * id);
    *regularized = true;
  }
  const MatrixXd sigma = llt.solve(id);
  return 0.5 * (sigma + sigma.transpose());
}

/// Edge p -> c (indices into nodes) at zero residual, and its Jacobian over x (N[0] held).
NfrJacobian JacobianOf(const std::vector<NodeId>& nodes, const Values& values, int p, int c) {
  const Pose2& Xp = values.at(nodes[static_cast<std::size_t>(p)]);
  const Pose2& Xc = values.at(nodes[static_cast<std::size_t>(c)]);
  NfrJacobian j;
  RelativeErrorJacobians(Xp, Xc, Between(Xp, Xc), &j.J_from, &j.J_to);
  j.from = p - 1;
  j.to = c - 1;
  return j;
}

}  // namespace

NfrFactors RecoverFactors(const std::vector<NodeId>& nodes, const Values& values,
                          const MatrixXd& lambda_N,
                          const std::vector<std::pair<std::size_t, std::size_t>>& candidates,
                          std::size_t max_extra, const NfrOptions& options) {
  NfrFactors out;
  const int m = static_cast<int>(nodes.size());
  if (m < 2) return out;
  const MatrixXd sigma = AnchoredSigma(lambda_N, &out.regularized);
  // The chow-liu sparsifier's tree: its gauge-free pair weights, Kruskal, away from N[0].
  const MatrixXd w = CliquePairWeights(nodes, values, lambda_N);
  std::vector<WeightedPair> pairs;
  for (int i = 0; i < m; ++i) {
    for (int j = i + 1; j < m; ++j) pairs.push_back({i, j, w(i, j)});
  }
  std::vector<std::pair<int, int>> topology;  // (from, to) indices into nodes
  std::set<std::pair<int, int>> taken;        // (min, max)
  for (const TreeEdge& t : OrientTree(m, MaximumSpanningTree(m, pairs), 0)) {
    topology.emplace_back(t.parent, t.child);
    taken.insert({std::min(t.parent, t.child), std::max(t.parent, t.child)});
  }
  const std::size_t tree_size = topology.size();
  std::vector<std::tuple<double, int, int>> extra;  // (-weight, i, j): strongest first
  for (const auto& [a, b] : candidates) {
    const int i = static_cast<int>(std::min(a, b)), j = static_cast<int>(std::max(a, b));
    if (i == j || j >= m || !taken.insert({i, j}).second) continue;
    extra.emplace_back(-w(i, j), i, j);
  }
  std::sort(extra.begin(), extra.end());
  if (extra.size() > max_extra) extra.resize(max_extra);
  for (const auto& [neg_weight, i, j] : extra) topology.emplace_back(i, j);
  std::vector<NfrJacobian> jacobians;
  for (const auto& [p, c] : topology) jacobians.push_back(JacobianOf(nodes, values, p, c));
  // Step 4 for the tree; its solution (extra edges at 0) starts step 5.
  std::vector<Matrix3d> info = NfrTreeInformation(sigma, jacobians);
  for (std::size_t i = tree_size; i < info.size(); ++i) info[i].setZero();
  if (topology.size() > tree_size) {
    out.solver = SolveNfr(sigma, jacobians, info, options);
    info = out.solver.information;
  } else {
    out.solver.information = info;
    out.solver.kl = NfrKl(sigma, jacobians, info);
    out.solver.converged = true;
  }
  for (std::size_t e = 0; e < topology.size(); ++e) {
    if (e >= tree_size) {  // whitened size ||S^1/2 Omega S^1/2||_F, S = J Sigma J^T
      const Matrix3d s = NfrTreeInformation(sigma, {jacobians[e]})[0].inverse();
      const double size2 = (s * info[e] * s * info[e]).trace();
      if (!(size2 >= kZeroInformation * kZeroInformation)) continue;
    }
    const auto p = static_cast<std::size_t>(topology[e].first);
    const auto c = static_cast<std::size_t>(topology[e].second);
    PoseEdge edge;
    edge.from = nodes[p];
    edge.to = nodes[c];
    edge.T_from_to = Between(values.at(nodes[p]), values.at(nodes[c]));
    edge.information = 0.5 * (info[e] + info[e].transpose());
    edge.kind = EdgeKind::kMarginal;
    out.edges.push_back(edge);
  }
  return out;
}

Replacement NfrReplace(const PoseGraph& graph, const Values& values, NodeId k,
                       const SparsifierConfig& config, bool subgraph) {
  const bool within = config.blanket == BlanketPolicy::kBlanket;
  // Lambda_N exactly as chow-liu (Marginalize) computes it, so both see the same pair weights
  // and take the same tree: rounding differences would break ties (M3500's equal edges make
  // many) the other way and the two methods would drift apart removal by removal.
  const LocalHessian local = LinearizeAround(graph, values, k, config.blanket);
  Replacement r;
  r.neighbours = local.neighbours;
  const std::vector<NodeId>& nodes = r.neighbours;
  if (nodes.size() < 2) return r;  // a leaf drops out
  r.absorb_edges_within = within;
  const MatrixXd lambda_N = SchurComplementFirstBlock(local.H);
  std::vector<std::pair<std::size_t, std::size_t>> candidates;
  std::size_t budget = 0;
  if (subgraph) {
    const auto index = [&](NodeId n) {
      return static_cast<std::size_t>(std::lower_bound(nodes.begin(), nodes.end(), n) -
                                      nodes.begin());
    };
    if (config.nfr_chords == NfrChords::kJoined) {
      for (const PoseEdge& e : graph.EdgesWithin(nodes)) {
        candidates.emplace_back(index(e.from), index(e.to));
      }
    } else {
      for (std::size_t i = 0; i < nodes.size(); ++i) {
        for (std::size_t j = i + 1; j < nodes.size(); ++j) candidates.emplace_back(i, j);
      }
    }
    const double ratio = std::max(config.nfr_chord_ratio, 0.0);
    budget = static_cast<std::size_t>(std::floor(ratio * static_cast<double>(nodes.size() - 1)));
  }
  NfrFactors f = RecoverFactors(nodes, values, lambda_N, candidates, budget);
  r.edges = std::move(f.edges);
  r.regularized = f.regularized;
  r.kl_divergence = GaugeFixedKl(lambda_N, FactorsHessian(nodes, values, r.edges, {}));
  KeepGradientIfAsked(config, graph, values, k, within, false, &r);
  return r;
}

}  // namespace lifelong::slam
