// Information-theoretic node removal (seed §5.1): among the nodes near the current one
// (Dijkstra expansion), remove the one whose scan has the lowest information gain
// I(z_i) = H(m without z_i) - H(m) while it is <= the threshold (or while the graph is over
// its node budget), updating the gains after each removal. Removal marginalizes the node
// (seed §5.3-5.5) with the configured method.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>

#include "slam/dijkstra.hpp"
#include "slam/mapper_state.hpp"
#include "slam/marginalization.hpp"
#include "slam/optimizer_problem.hpp"
#include "slam/se2.hpp"
#include "slam/sparsifier.hpp"

namespace lifelong::slam {
Mapper::State::State(const MapperConfig& c)
    : config(c), closer(c.loops, c.incremental), map(c.grid) {
  if (const std::optional<ConfigProblem> problem = Validate(c)) {
    throw std::invalid_argument("mapper config: " + problem->fields + ": " + problem->message);
  }
  if (c.pruning.mode == PruningMode::kNone) return;
  prune_state.policy =
      MakeRemovalPolicy(c.pruning.policy, {c.pruning.gain_threshold_bits, c.pruning.node_budget});
  if (!prune_state.policy)
    throw std::invalid_argument("unknown removal policy '" + c.pruning.policy + "'");
  const std::string name =
      c.pruning.sparsifier.empty() ? ModeSparsifier(c.pruning.mode) : c.pruning.sparsifier;
  SparsifierConfig sc;
  sc.blanket = c.pruning.blanket;
  sc.nfr_chords = c.pruning.nfr_chords;
  sc.nfr_chord_ratio = c.pruning.nfr_chord_ratio;
  sc.means = c.pruning.factor_means;
  prune_state.sparsifier = MakeSparsifier(name, sc);
  if (!prune_state.sparsifier) throw std::invalid_argument("unknown sparsifier '" + name + "'");
}

std::vector<WeighedEdge> WeighRobustEdges(PoseGraph* graph, const Values& values,
                                          const std::vector<NodeId>& set,
                                          const OptimizerParams& params) {
  const auto in = [&](NodeId n) { return std::binary_search(set.begin(), set.end(), n); };
  std::vector<WeighedEdge> out;
  for (std::size_t i = 0; i < graph->edges().size(); ++i) {
    const PoseEdge& e = graph->edges()[i];
    if (!e.robust || !in(e.from) || !in(e.to)) continue;
    const Eigen::Vector3d r = RelativeError(values.at(e.from), values.at(e.to), e.T_from_to);
    const double w = backend::ApplyKernel(r.dot(e.information * r), true, params).weight;
    out.push_back({i, e.information});
    graph->SetEdgeInformation(i, w * e.information);
  }
  return out;
}

void Mapper::State::Prune(NodeId current) {
  const PruningConfig& pc = config.pruning;
  // Marginalization linearizes at the current estimate and keeps its means for good, so the
  // estimate must be the optimum: settle any loop closure not yet optimized (cheap here, the
  // pruned graph is small). The map is not re-rendered for it: it follows the estimate on the
  // schedule it follows in standard mode (loops.optimize_edge_chi2, optimize_every), and the
  // gains are those of the map as rendered. Re-rendering before every round moved each scan
  // once per closure: 4x the optimizations and 3x the map update on Intel (BENCHMARKS.md).
  if (since_optimize > 0) Optimize();
  const NodeId anchor = graph.NodeIds().front();
  std::set<NodeId> protected_ids{current, anchor};
  // Never marginalize a closure that is not settled: a pending hypothesis would lose its
  // nodes, and a suspect loop edge would be baked into factors no kernel can switch off.
  const std::set<NodeId> unsettled = UnsettledNodes();
  protected_ids.insert(unsettled.begin(), unsettled.end());
  for (int i = 0; i < pc.keep_recent_nodes && i < static_cast<int>(recent.size()); ++i) {
    protected_ids.insert(recent[recent.size() - 1 - static_cast<std::size_t>(i)]);
  }
  const Pose2& X_cur = values.at(current);
  std::map<NodeId, double> gains;
  for (const auto& [id, length] : ExpandByPathLength(graph, values, current, 3.0 * pc.radius_m)) {
    const Pose2& X = values.at(id);
    if (protected_ids.count(id) || std::hypot(X.x - X_cur.x, X.y - X_cur.y) > pc.radius_m) {
      continue;
    }
    gains[id] = 0.0;
  }
  for (auto& [id, gain] : gains) gain = Gain(id);

  while (!gains.empty()) {
    const std::optional<NodeId> next = prune_state.policy->Next(gains, graph.NumNodes());
    if (!next) break;
    const NodeId victim = *next;
    const double gain = gains.at(victim);
    gains.erase(victim);
    RemoveNode(victim, gain);
    // The index has updated the gains of the scans that shared cells with it.
    for (auto& [id, g] : gains) g = Gain(id);
  }
  if (prune_state.sparsifier->Name() == "chow-liu" && pc.max_edges_per_node > 0.0) KeepEdgeBudget();
}

void Mapper::State::KeepEdgeBudget() {
  const ScopedMs timer = Stage(&StageTimes::marginalize_ms);
  // The nodes within `hops` edges of `centre`, ascending.
  const auto ball = [this](NodeId centre, int hops) {
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
  };
  // Edges beyond a spanning tree among the nodes of a (connected) ball: its cycle rank.
  const auto excess = [this](const std::vector<NodeId>& set) {
    std::size_t within = 0;
    for (NodeId a : set) {
      for (NodeId b : graph.Neighbours(a)) {
        within += (a < b && std::binary_search(set.begin(), set.end(), b)) ? 1 : 0;
      }
    }
    return within + 1 > set.size() ? within + 1 - set.size() : 0;
  };
  // Bounds the work of one observation; the budget is restored over the next ones if need be.
  constexpr int kMaxPerRound = 16;
  for (int done = 0; done < kMaxPerRound; ++done) {
    const double num_nodes = static_cast<double>(graph.NumNodes());
    if (static_cast<double>(graph.NumEdgesForGamma()) <=
        config.pruning.max_edges_per_node * num_nodes)
      return;
    // The Markov blanket (one hop) with the most edges beyond a tree; when every blanket is
    // a tree already, the two-hop neighbourhood with the most.
    std::vector<NodeId> best;
    std::size_t most = 0;
    NodeId centre = 0;
    const std::set<NodeId> unsettled = UnsettledNodes();
    const auto settled = [&](const std::vector<NodeId>& set) {
      return std::none_of(set.begin(), set.end(), [&](NodeId n) { return unsettled.count(n); });
    };
    for (int hops = 1; hops <= 2 && most == 0; ++hops) {
      for (const auto& [id, unused] : nodes) {
        std::vector<NodeId> set = ball(id, hops);
        if (!settled(set)) continue;
        const std::size_t e = excess(set);
        if (e > most) {
          most = e;
          centre = id;
          best = std::move(set);
        }
      }
    }
    if (most == 0) return;  // the graph is a tree near every node
    std::vector<WeighedEdge> weighed;
    if (config.pruning.robust_marginal)
      weighed = WeighRobustEdges(&graph, values, best, config.optimizer);
    SparsificationResult result = SparsifyWithin(graph, values, best);
    if (!result.applied) {
      for (const WeighedEdge& w : weighed) graph.SetEdgeInformation(w.index, w.information);
      return;
    }
    if (config.pruning.factor_means != FactorMeans::kEstimate) {  // keep the edges' pull too
      const LocalSystem replaced = LinearizeEdges(best, values, graph.EdgesWithin(best));
      std::vector<CliqueFactor> no_cliques;
      MoveMeans(config.pruning.factor_means, best, values, replaced.H, replaced.g, &result.edges,
                &no_cliques);
    }
    ApplySparsification(&graph, result);
    prune_state.sparsifications.push_back(
        {centre, best.size(), result.edges_before, result.edges.size(), result.kl_divergence});
  }
}

void Mapper::State::RemoveNode(NodeId id, double gain_bits) {
  const ScopedMs timer = Stage(&StageTimes::marginalize_ms);
  // With robust_marginal, the loop edges of the clique (at the node and among its
  // neighbours) enter the marginal as the optimizer weighs them at the estimate: information
  // times the kernel's IRLS weight rho'(e^T Omega e). Those among the neighbours that the
  // sparsifier leaves in the graph get their own information back.
  std::vector<WeighedEdge> weighed;
  if (config.pruning.robust_marginal) {
    std::vector<NodeId> clique(graph.Neighbours(id).begin(), graph.Neighbours(id).end());
    clique.insert(std::lower_bound(clique.begin(), clique.end(), id), id);
    weighed = WeighRobustEdges(&graph, values, clique, config.optimizer);
  }
  const Replacement replacement = prune_state.sparsifier->Replace(graph, values, id);
  if (!replacement.absorb_edges_within) {
    for (const WeighedEdge& w : weighed) {
      const PoseEdge& e = graph.edges()[w.index];
      if (e.from != id && e.to != id) graph.SetEdgeInformation(w.index, w.information);
    }
  }
  // The removed node's scans are held relative to its nearest surviving neighbour.
  const Pose2& X = values.at(id);
  NodeId keeper = id;
  double best = std::numeric_limits<double>::infinity();
  for (NodeId n : graph.Neighbours(id)) {
    const double d = std::hypot(values.at(n).x - X.x, values.at(n).y - X.y);
    if (d < best) {
      best = d;
      keeper = n;
    }
  }
  const Pose2 T_keeper_node = Between(values.at(keeper), X);
  const std::vector<std::size_t> held = scans_of_node[id];
  for (std::size_t scan : held) {
    scans[scan].T_anchor_scan = T_keeper_node * scans[scan].T_anchor_scan;
    Reanchor(scan, keeper);
  }
  scans_of_node.erase(id);
  ChangeMap(Untrack(id), false);
  ApplyReplacement(&graph, id, replacement);
  prune_state.marginalizations.push_back(
      {id, replacement.neighbours.size(), replacement.kl_divergence, gain_bits});
  nodes.erase(id);
  values.erase(id);
  closer.ForgetNode(id);
  recent.erase(std::find(recent.begin(), recent.end(), id));
  if (last_node == id) last_node = recent.back();
}

}  // namespace lifelong::slam
