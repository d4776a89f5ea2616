// The mapper's side of loop closing: it runs the loop closer's searches for the new node
// (slam/loops/loop_closer.hpp) and puts the closures they accept into the graph, optimizing when a
// new edge is far off.
#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "slam/graph/se2.hpp"
#include "slam/mapping/mapper_state.hpp"

namespace lifelong::slam {

void Mapper::State::CloseLoops(NodeId current, StepStats* stats) {
  std::vector<LoopHypothesis> accepted;
  const std::optional<LoopAttempt> local =
      closer.SearchLocal(View(), current, observations, &accepted);
  if (local) stats->loop_attempts.push_back(*local);
  // Each closure goes in as it was accepted: AddLoopEdge may optimize before the next.
  for (const LoopHypothesis& h : accepted) AddLoopEdge(h);
  stats->loop_closed = !accepted.empty();
  // The global search reuses the local one's covariance projection: it runs only when that
  // closed nothing, so the estimate is as it was projected.
  const GlobalLoopConfig& global = config.loops.global;
  const bool search = !stats->loop_closed && observations % global.every == 0 &&
                      nodes.at(current).travelled_m - closed_at_m >= global.after_m;
  accepted.clear();
  const std::optional<LoopAttempt> wide = closer.SearchGlobal(View(), current, search, &accepted);
  if (wide) stats->loop_attempts.push_back(*wide);
  for (const LoopHypothesis& h : accepted) AddLoopEdge(h);
  if (!accepted.empty()) stats->loop_closed = true;
}

void Mapper::State::AddLoopEdge(const LoopHypothesis& h) {
  const LoopClosingConfig& lc = config.loops;
  PoseEdge edge;
  edge.from = h.old;
  edge.to = h.current;
  edge.kind = EdgeKind::kLoop;
  edge.robust = true;
  edge.T_from_to = h.T_old_current;
  edge.information = h.information;
  graph.AddEdge(edge);
  closed_at_m = std::max(closed_at_m, nodes.at(h.current).travelled_m);
  loops.push_back({h.current, h.old,
                   scans.stamp(static_cast<std::size_t>(nodes.at(h.current).scan_index)),
                   scans.stamp(static_cast<std::size_t>(nodes.at(h.old).scan_index)),
                   edge.T_from_to, h.injected});
  ++since_optimize;
  ++since_sync;
  const double chi2 =
      EdgeChi2(values.at(h.old), values.at(h.current), edge.T_from_to, edge.information);
  if (chi2 > lc.optimize_edge_chi2 || since_sync >= lc.optimize_every) {
    OptimizeAndSyncMap();
  }
}

std::vector<std::optional<double>> Mapper::LoopEdgeChi2() const {
  const State& s = *state_;
  std::map<std::pair<NodeId, NodeId>, double> chi2;  // (old, current) -> chi2
  for (const PoseEdge& edge : s.graph.edges()) {
    if (edge.kind != EdgeKind::kLoop) continue;
    chi2[{edge.from, edge.to}] =
        EdgeChi2(s.values.at(edge.from), s.values.at(edge.to), edge.T_from_to, edge.information);
  }
  std::vector<std::optional<double>> out;
  out.reserve(s.loops.size());
  for (const LoopClosureRecord& r : s.loops) {
    const auto it = chi2.find({r.old, r.current});
    out.push_back(it == chi2.end() ? std::nullopt : std::optional<double>(it->second));
  }
  return out;
}

int Mapper::SuspectLoopEdges() const {
  int n = 0;
  for (const std::optional<double>& chi2 : LoopEdgeChi2()) {
    n += chi2 && *chi2 > state_->config.loops.suspect_chi2 ? 1 : 0;
  }
  return n;
}

std::set<NodeId> Mapper::State::UnsettledNodes() const {
  std::set<NodeId> out;
  for (const LoopHypothesis& h : closer.pending()) {
    out.insert(h.old);
    out.insert(h.current);
  }
  for (const PoseEdge& edge : graph.edges()) {
    if (edge.kind != EdgeKind::kLoop) continue;
    const auto a = values.find(edge.from), b = values.find(edge.to);
    if (a == values.end() || b == values.end()) continue;
    if (EdgeChi2(a->second, b->second, edge.T_from_to, edge.information) >
        config.loops.suspect_chi2) {
      out.insert(edge.from);
      out.insert(edge.to);
    }
  }
  return out;
}

}  // namespace lifelong::slam
