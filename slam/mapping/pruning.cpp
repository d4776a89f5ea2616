// Pruning rounds (seed §5.1): among the nodes near the current one (Dijkstra expansion), the
// pruner's policy removes the one whose scan has the lowest information gain
// I(z_i) = H(m without z_i) - H(m) while it says so, the gains updated after each removal.
// The pruner marginalizes the node (seed §5.3-5.5) in the graph (slam/mapping/pruner.hpp); here the
// mapper moves what it holds of the node: its scans to a neighbour, its cells out of the map.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "slam/backend/optimizer_problem.hpp"
#include "slam/graph/dijkstra.hpp"
#include "slam/graph/se2.hpp"
#include "slam/grid/beam_cut.hpp"
#include "slam/mapping/mapper_state.hpp"
#include "slam/marginal/marginalization.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {

void Mapper::State::Prune(NodeId current) {
  const PruningConfig& pc = config.pruning;
  // Marginalization linearizes at the current estimate and keeps its means for good, so the
  // estimate must be the optimum: settle any loop closure not yet optimized (cheap here, the
  // pruned graph is small). The map is not re-rendered for it: it follows the estimate on the
  // schedule it follows in standard mode (loops.optimize_edge_chi2, optimize_every), and the
  // gains are those of the map as rendered. Re-rendering before every round moved each scan
  // once per closure: 4x the optimizations and 3x the map update on Intel (docs/results.md).
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
  RoundView view;
  const std::map<NodeId, double> reached =
      ExpandByPathLength(graph, values, current, 3.0 * pc.radius_m);
  for (const auto& [id, length] : reached) {
    const Pose2& X = values.at(id);
    if (id == current || std::hypot(X.x - X_cur.x, X.y - X_cur.y) > pc.radius_m) continue;
    view.nearby.push_back(id);
    if (!protected_ids.count(id)) gains[id] = 0.0;
  }
  std::sort(view.nearby.begin(), view.nearby.end());
  TrackGainsAround(X_cur, view.nearby);
  for (auto& [id, gain] : gains) gain = keeper.Gain(id);
  BindRoundView(current, &view);
  std::vector<SampleRetirement> retired;
  {
    const ScopedMs timer = Stage(&StageTimes::gain_ms);
    retired = pruner->BeginRound(gains, view);
  }
  for (const SampleRetirement& r : retired) CutBeams(r.node, r.cuts);
  if (!retired.empty()) {
    for (auto& [id, gain] : gains) gain = keeper.Gain(id);
  }

  while (!gains.empty()) {
    const std::optional<NodeId> next = pruner->Next(gains, graph.NumNodes());
    if (!next) break;
    const NodeId victim = *next;
    const double gain = gains.at(victim);
    gains.erase(victim);
    RemoveNode(victim, gain);
    // The index has updated the gains of the scans that shared cells with it.
    for (auto& [id, g] : gains) g = keeper.Gain(id);
  }
  const ScopedMs timer = Stage(&StageTimes::marginalize_ms);
  pruner->KeepEdgeBudget(&graph, values, [this] { return UnsettledNodes(); });
}

void Mapper::State::TrackGainsAround(const Pose2& X_cur, const std::vector<NodeId>& nearby) {
  // The map tracks the gains of the nodes within the radius and keeps tracking those within
  // five radii, a margin that spares the nodes of a building the robot walks around a fresh
  // trace at each return; it forgets the others' and computes them afresh when the robot
  // comes back (a campus's far streets).
  std::vector<NodeId> kept;
  const double margin_m = 5.0 * config.pruning.radius_m;
  for (const auto& [id, X] : values) {
    if (std::hypot(X.x - X_cur.x, X.y - X_cur.y) <= margin_m) kept.push_back(id);
  }
  keeper.TrackOnly(nearby, kept, nodes);
}

void Mapper::State::BindRoundView(NodeId current, RoundView* view) const {
  view->current = current;
  view->local_map_from = sequential.OldestRemembered().value_or(current);
  view->within = [this, current](double radius_m) {
    const Pose2& c = values.at(current);
    std::vector<NodeId> out;
    for (const NodeId id : graph.NodeIds()) {
      const Pose2& X = values.at(id);
      if (id != current && std::hypot(X.x - c.x, X.y - c.y) <= radius_m) out.push_back(id);
    }
    return out;
  };
  view->footprint = [this](NodeId id) { return Footprint(id); };
  view->scan = [this](NodeId id) {
    const NodeData& data = nodes.at(id);
    return ScanAt{&data.scan, &data.cuts, values.at(id)};
  };
}

ScanFootprint Mapper::State::Footprint(NodeId id) const {
  ScanFootprint f;
  f.points = ToWorld(nodes.at(id).points, values.at(id));
  for (const Eigen::Vector2d& p : f.points) {
    f.box.extend(p);
    f.centre += p;
  }
  if (!f.points.empty()) f.centre /= static_cast<double>(f.points.size());
  f.edges = static_cast<int>(graph.Neighbours(id).size());
  return f;
}

void Mapper::State::CutBeams(NodeId id, const std::vector<BeamCut>& cuts) {
  NodeData& data = nodes.at(id);
  std::vector<BeamCut> merged = MergeCuts(data.cuts, cuts);
  keeper.Retrace(id, data.scan, data.T_world_map, data.cuts, merged);
  data.cuts = std::move(merged);
  cut_beams += cuts.size();
}

void Mapper::State::RemoveNode(NodeId id, double gain_bits) {
  const ScopedMs timer = Stage(&StageTimes::marginalize_ms);
  const Replacement replacement = pruner->Marginalize(&graph, values, id);
  // The removed node's scans are held relative to its nearest surviving neighbour.
  const Pose2& X = values.at(id);
  NodeId heir = id;
  double best = std::numeric_limits<double>::infinity();
  for (NodeId n : graph.Neighbours(id)) {
    const double d = std::hypot(values.at(n).x - X.x, values.at(n).y - X.y);
    if (d < best) {
      best = d;
      heir = n;
    }
  }
  scans.Handover(id, heir, Between(values.at(heir), X));
  const NodeData& data = nodes.at(id);
  keeper.Remove(id, data.scan, data.T_world_map, data.cuts);
  pruner->Remove(&graph, id, replacement, gain_bits);
  nodes.erase(id);
  values.erase(id);
  closer.ForgetNode(id);
  recent.erase(std::find(recent.begin(), recent.end(), id));
  if (last_node == id) last_node = recent.back();
}

}  // namespace lifelong::slam
