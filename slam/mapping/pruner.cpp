// The pruner: removal policy, sparsifier, the marginalization step and the edge budget
// (pruner.hpp).
#include "slam/mapping/pruner.hpp"

#include <algorithm>
#include <functional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "slam/backend/optimizer_problem.hpp"
#include "slam/graph/se2.hpp"
#include "slam/marginal/marginalization.hpp"

namespace lifelong::slam {

std::vector<WeighedEdge> WeighRobustEdges(PoseGraph* graph, const Values& values,
                                          const std::vector<NodeId>& set,
                                          const OptimizerParams& params) {
  const auto in = [&](NodeId n) { return std::binary_search(set.begin(), set.end(), n); };
  std::vector<WeighedEdge> out;
  for (std::size_t i = 0; i < graph->edges().size(); ++i) {
    const PoseEdge& e = graph->edges()[i];
    if (!e.robust || !in(e.from) || !in(e.to)) continue;
    const double chi2 = EdgeChi2(values.at(e.from), values.at(e.to), e.T_from_to, e.information);
    const double w = backend::ApplyKernel(chi2, true, params).weight;
    out.push_back({i, e.information});
    graph->SetEdgeInformation(i, w * e.information);
  }
  return out;
}

Pruner::Pruner(const PruningConfig& config, const OptimizerParams& optimizer)
    : config_(config), optimizer_(optimizer) {
  const std::string& policy = config.mode.policy;
  policy_ = MakeRemovalPolicy(
      policy, {config.gain_threshold_bits, config.node_budget, config.overlap, config.dpg});
  if (!policy_) throw std::invalid_argument("unknown removal policy '" + policy + "'");
  const std::string& name = config.mode.sparsifier;
  SparsifierConfig sc;
  sc.blanket = config.blanket;
  sc.nfr_chords = config.nfr_chords;
  sc.nfr_chord_ratio = config.nfr_chord_ratio;
  sc.means = config.factor_means;
  sparsifier_ = MakeSparsifier(name, sc);
  if (!sparsifier_) throw std::invalid_argument("unknown sparsifier '" + name + "'");
}

std::optional<NodeId> Pruner::Next(const std::map<NodeId, double>& gains,
                                   std::size_t num_nodes) const {
  return policy_->Next(gains, num_nodes);
}

Replacement Pruner::Marginalize(PoseGraph* graph, const Values& values, NodeId id) const {
  // With robust_marginal, the loop edges of the clique (at the node and among its
  // neighbours) enter the marginal as the optimizer weighs them at the estimate: information
  // times the kernel's IRLS weight rho'(e^T Omega e). Those among the neighbours that the
  // sparsifier leaves in the graph get their own information back.
  std::vector<WeighedEdge> weighed;
  if (config_.robust_marginal) {
    std::vector<NodeId> clique(graph->Neighbours(id).begin(), graph->Neighbours(id).end());
    clique.insert(std::lower_bound(clique.begin(), clique.end(), id), id);
    weighed = WeighRobustEdges(graph, values, clique, optimizer_);
  }
  Replacement replacement = sparsifier_->Replace(*graph, values, id);
  if (!replacement.absorb_edges_within) {
    for (const WeighedEdge& w : weighed) {
      const PoseEdge& e = graph->edges()[w.index];
      if (e.from != id && e.to != id) graph->SetEdgeInformation(w.index, w.information);
    }
  }
  return replacement;
}

std::vector<SampleRetirement> Pruner::BeginRound(const std::map<NodeId, double>& gains,
                                                 const RoundView& view) {
  policy_->BeginRound(gains, view);
  return policy_->TakeRetirements();
}

void Pruner::Remove(PoseGraph* graph, NodeId id, const Replacement& replacement, double gain_bits) {
  ApplyReplacement(graph, id, replacement);
  policy_->Forget(id);
  removals_.push_back({id, replacement.neighbours.size(), replacement.kl_divergence, gain_bits});
}

namespace {

/// The nodes within `hops` edges of `centre`, ascending.
std::vector<NodeId> Ball(const PoseGraph& graph, NodeId centre, int hops) {
  std::set<NodeId> in{centre}, frontier{centre};
  for (int h = 0; h < hops; ++h) {
    std::set<NodeId> next;
    for (NodeId u : frontier) {
      for (NodeId w : graph.Neighbours(u)) {
        if (in.insert(w).second) next.insert(w);
      }
    }
    frontier = std::move(next);
  }
  return std::vector<NodeId>(in.begin(), in.end());
}

/// Edges beyond a spanning tree among the nodes of a (connected) ball: its cycle rank.
std::size_t CycleRank(const PoseGraph& graph, const std::vector<NodeId>& set) {
  std::size_t within = 0;
  for (NodeId a : set) {
    for (NodeId b : graph.Neighbours(a)) {
      within += (a < b && std::binary_search(set.begin(), set.end(), b)) ? 1 : 0;
    }
  }
  return within + 1 > set.size() ? within + 1 - set.size() : 0;
}

struct Neighbourhood {
  NodeId centre = 0;
  std::vector<NodeId> nodes;
  std::size_t excess = 0;  ///< edges beyond a tree; 0: none found
};

/// The Markov blanket (one hop) with the most edges beyond a tree; when every blanket is a
/// tree already, the two-hop neighbourhood with the most. Neighbourhoods holding an
/// unsettled node are passed over.
Neighbourhood DensestNeighbourhood(const PoseGraph& graph, const std::set<NodeId>& unsettled) {
  const auto settled = [&](const std::vector<NodeId>& set) {
    return std::none_of(set.begin(), set.end(), [&](NodeId n) { return unsettled.count(n); });
  };
  Neighbourhood best;
  for (int hops = 1; hops <= 2 && best.excess == 0; ++hops) {
    for (NodeId id : graph.NodeIds()) {
      std::vector<NodeId> set = Ball(graph, id, hops);
      if (!settled(set)) continue;
      const std::size_t e = CycleRank(graph, set);
      if (e > best.excess) best = {id, std::move(set), e};
    }
  }
  return best;
}

}  // namespace

void Pruner::KeepEdgeBudget(PoseGraph* graph_ptr, const Values& values,
                            const std::function<std::set<NodeId>()>& unsettled_nodes) {
  if (!sparsifier_->LeavesTrees() || config_.max_edges_per_node <= 0.0) return;
  PoseGraph& graph = *graph_ptr;
  // Bounds the work of one observation; the budget is restored over the next ones if need be.
  constexpr int kMaxPerRound = 16;
  for (int done = 0; done < kMaxPerRound; ++done) {
    const double num_nodes = static_cast<double>(graph.NumNodes());
    if (static_cast<double>(graph.NumEdgesForGamma()) <= config_.max_edges_per_node * num_nodes)
      return;
    const Neighbourhood n = DensestNeighbourhood(graph, unsettled_nodes());
    if (n.excess == 0) return;  // the graph is a tree near every node
    const std::vector<NodeId>& best = n.nodes;
    std::vector<WeighedEdge> weighed;
    if (config_.robust_marginal) weighed = WeighRobustEdges(&graph, values, best, optimizer_);
    SparsificationResult result = SparsifyWithin(graph, values, best);
    if (!result.applied) {
      for (const WeighedEdge& w : weighed) graph.SetEdgeInformation(w.index, w.information);
      return;
    }
    if (config_.factor_means != FactorMeans::kEstimate) {  // keep the edges' pull too
      const LocalSystem replaced = LinearizeEdges(best, values, graph.EdgesWithin(best));
      std::vector<CliqueFactor> no_cliques;
      MoveMeans(config_.factor_means, best, values, replaced.H, replaced.g, replaced.chi2,
                &result.edges, &no_cliques);
    }
    ApplySparsification(&graph, result);
    sparsified_.push_back(
        {n.centre, best.size(), result.edges_before, result.edges.size(), result.kl_divergence});
  }
}

}  // namespace lifelong::slam
