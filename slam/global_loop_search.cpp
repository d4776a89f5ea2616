// Global loop closing (loops.global; mapper_config.hpp GlobalLoopConfig): candidates come
// from the place index, not from the projected uncertainty, so a revisit is found however far
// the estimate has drifted. Each candidate is matched by the correlative matcher's branch and
// bound in a window of loops.global.linear_window_m around the candidate node's position, at
// the heading the descriptors agree on, against the candidate and its graph neighbours. A
// match must pass the local search's tests (score, ambiguity, local uniqueness) and then the
// same group verification (slam/loop_verifier.hpp) before it enters the graph; only the test
// against the projected uncertainty is left out, since the drift is what is being corrected.
#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include <Eigen/LU>

#include "slam/mapper_state.hpp"
#include "slam/scan_matcher.hpp"

namespace lifelong::slam {

PlaceDescriptor Mapper::State::DescribeNode(NodeId id) const {
  const GlobalLoopConfig& g = config.loops.global;
  const Pose2& X = values.at(id);
  std::vector<Eigen::Vector2d> points;
  const auto count = static_cast<std::ptrdiff_t>(std::max(g.context_nodes, 0) + 1);
  const auto it = std::find(recent.begin(), recent.end(), id);
  const auto last = it == recent.end() ? recent.end() : std::next(it);
  const auto first = last - std::min(count, last - recent.begin());
  for (auto n = first; n != last; ++n) {
    const Pose2 T_id_n = Between(X, values.at(*n));
    for (const Eigen::Vector2d& p : nodes.at(*n).points) {
      double x = 0.0, y = 0.0;
      T_id_n.Apply(p.x(), p.y(), &x, &y);
      points.emplace_back(x, y);
    }
  }
  return DescribePlace(points, g.descriptor);
}

bool Mapper::State::TryGlobalLoop(NodeId current, const PlaceDescriptor& place) {
  const LoopClosingConfig& lc = config.loops;
  const GlobalLoopConfig& g = lc.global;
  const NodeData& cur = nodes.at(current);
  struct Proposal {
    NodeId id;
    PlaceComparison cmp;
  };
  std::vector<Proposal> proposals;
  for (NodeId id : places.Nearest(place, static_cast<std::size_t>(g.index_neighbours))) {
    const auto node = nodes.find(id);
    if (node == nodes.end()) continue;
    // Not a revisit: the robot has not left this place (odometry path length).
    if (cur.travelled_m - node->second.travelled_m < lc.min_path_separation_m) continue;
    const PlaceComparison cmp = ComparePlaces(place, places.Get(id));
    if (cmp.distance <= g.max_distance) proposals.push_back({id, cmp});
  }
  if (proposals.empty()) return false;
  std::sort(proposals.begin(), proposals.end(),
            [](const Proposal& a, const Proposal& b) { return a.cmp.distance < b.cmp.distance; });
  if (static_cast<int>(proposals.size()) > g.candidates) proposals.resize(g.candidates);

  loop_state.verifier.NoteGlobalAttempt();
  MatchRefusal why = MatchRefusal::kLowScore;
  for (const Proposal& p : proposals) {
    // The current scan placed at the candidate, turned by the descriptors' heading.
    const Pose2& X_old = values.at(p.id);
    const Pose2 guess = X_old * Pose2(0.0, 0.0, p.cmp.yaw_rad);
    std::set<NodeId> submap{p.id};
    int added = 0;
    for (NodeId n : graph.Neighbours(p.id)) {
      if (added++ >= lc.neighbours_per_candidate) break;
      submap.insert(n);
    }
    std::vector<Eigen::Vector2d> reference;
    for (NodeId id : submap) {
      const std::vector<Eigen::Vector2d> pts = LoopReference(id);
      reference.insert(reference.end(), pts.begin(), pts.end());
    }
    MatcherConfig mc = lc.matcher;
    mc.linear_window_m = g.linear_window_m;
    mc.angular_window_rad = g.angular_window_rad;
    CropToSearch(cur.points, guess, mc, &reference);
    if (static_cast<int>(reference.size()) < lc.min_reference_points) {
      why = MatchRefusal::kFewPoints;
      continue;
    }
    match_grid.Build(reference, mc);
    const MatchResult match = Match(match_grid, cur.points, guess, mc);
    if (!match.ok || match.score < lc.min_score) {
      why = MatchRefusal::kLowScore;
      continue;
    }
    if (match.ambiguity > lc.max_ambiguity) {
      why = MatchRefusal::kAmbiguous;
      continue;
    }
    if (!LocallyUnique(match, cur.points)) {
      why = MatchRefusal::kNotUnique;
      continue;
    }
    const MatchResult pair = RefineAgainstNode(p.id, cur.points, match);
    LoopHypothesis h;
    h.old = p.id;
    h.current = current;
    h.T_old_current = Between(X_old, pair.T_ref_cur);
    h.information = RotateIntoFrame(pair.information, pair.T_ref_cur.theta);
    h.covariance = h.information.inverse();
    h.travelled_m = cur.travelled_m;
    MaybeInjectFalse(&h);
    loop_state.verifier.NoteGlobalProposed();
    bool closed = false;
    for (const LoopHypothesis& accepted : loop_state.verifier.Add(h, values)) {
      AddLoopEdge(accepted);
      closed = true;
    }
    return closed;
  }
  loop_state.verifier.NoteRefused(why);
  return false;
}

}  // namespace lifelong::slam
