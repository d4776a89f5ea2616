// Information-theoretic node removal (seed §5.1): among the nodes near the current one
// (Dijkstra expansion), remove the one whose scan has the lowest information gain
// I(z_i) = H(m without z_i) - H(m) while it is <= the threshold (or while the graph is over
// its node budget), updating the gains after each removal. Removal marginalizes the node
// (seed §5.3-5.5) with the configured method.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "slam/dijkstra.hpp"
#include "slam/mapper_state.hpp"
#include "slam/marginalization.hpp"

namespace lifelong::slam {
namespace {

MarginalizationMethod MethodOf(PruningMode mode) {
  switch (mode) {
    case PruningMode::kExact:
      return MarginalizationMethod::kExact;
    case PruningMode::kNaive:
      return MarginalizationMethod::kNaive;
    default:
      return MarginalizationMethod::kChowLiu;
  }
}

}  // namespace

CellBounds BoxOf(const std::vector<CellUpdate>& cells) {
  CellBounds b;
  for (const CellUpdate& u : cells) {
    if (b.empty) {
      b.min = b.max = u.cell;
      b.empty = false;
    }
    b.min = {std::min(b.min.x, u.cell.x), std::min(b.min.y, u.cell.y)};
    b.max = {std::max(b.max.x, u.cell.x), std::max(b.max.y, u.cell.y)};
  }
  return b;
}

bool Overlap(const CellBounds& a, const CellBounds& b) {
  return !a.empty && !b.empty && a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y &&
         b.min.y <= a.max.y;
}

void Mapper::State::Prune(NodeId current) {
  const PruningConfig& pc = config.pruning;
  // Marginalization linearizes at the current estimate and keeps its means for good, so the
  // estimate must be the optimum: settle any loop closure not yet optimized (cheap here, the
  // pruned graph is small).
  if (closures_since_optimize > 0) OptimizeAndSyncMap();
  const NodeId anchor = graph.NodeIds().front();
  std::set<NodeId> protected_ids{current, anchor};
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
  // A remembered gain stays exact until the map changes inside its scan's box: every node
  // (not only this round's candidates) forgets its gain when a change since the last round
  // overlaps its box.
  for (auto& [id, data] : nodes) {
    for (const CellBounds& change : map_changes) {
      if (data.gain_valid && Overlap(data.box, change)) data.gain_valid = false;
    }
  }
  map_changes.clear();
  for (auto& [id, gain] : gains) {
    const NodeData& data = nodes.at(id);
    gain = data.gain_valid ? data.gain_bits : Gain(id);
  }
  std::set<NodeId> considered = protected_ids;
  for (const auto& [id, gain] : gains) considered.insert(id);

  while (!gains.empty()) {
    auto lowest = std::min_element(gains.begin(), gains.end(), [](const auto& a, const auto& b) {
      return a.second < b.second || (a.second == b.second && a.first < b.first);
    });
    const bool over_budget =
        pc.node_budget > 0 && static_cast<int>(graph.NumNodes()) > pc.node_budget;
    if (lowest->second > pc.gain_threshold_bits && !over_budget) break;
    const NodeId victim = lowest->first;
    const double gain = lowest->second;
    gains.erase(lowest);
    const CellBounds changed = nodes.at(victim).box;  // its gain, hence box, is current
    RemoveNode(victim, gain);
    // Only the gains of scans sharing cells with the removed one can have changed; the
    // nodes outside this round see the change at the next one.
    map_changes.push_back(changed);
    for (auto& [id, g] : gains) {
      if (Overlap(nodes.at(id).box, changed)) g = Gain(id);
    }
  }
  // The cell lists are a cache for the neighbourhood: free those of the nodes left behind,
  // so memory follows the neighbourhood, not the graph.
  for (auto& [id, data] : nodes) {
    if (!data.touched.empty() && !considered.count(id))
      std::vector<CellUpdate>().swap(data.touched);
  }
}

void Mapper::State::RemoveNode(NodeId id, double gain_bits) {
  const MarginalizationResult result =
      Marginalize(graph, values, id, MethodOf(config.pruning.mode), config.pruning.blanket);
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
  map.Remove(Touched(id));
  ApplyMarginalization(&graph, id, result);
  marginalizations.push_back({id, result.clique_size, result.kl_divergence, gain_bits});
  nodes.erase(id);
  values.erase(id);
  recent.erase(std::find(recent.begin(), recent.end(), id));
  if (last_node == id) last_node = recent.back();
}

}  // namespace lifelong::slam
