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

#include "slam/dijkstra.hpp"
#include "slam/mapper_state.hpp"
#include "slam/scan_matcher.hpp"
#include "slam/se2.hpp"

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
  // How far each candidate may be from where the estimate puts it: the Dijkstra projection
  // of the covariances (as the local search), inflated by plausible_sigmas; a candidate the
  // projection does not reach (position sigma past loops.max_position_sigma_m) may be
  // anywhere.
  ProjectionConfig projection;
  projection.max_position_sigma_m = lc.max_position_sigma_m;
  const auto projected = ProjectCovariances(graph, values, current, projection);
  // Every proposal is matched: a place that another, distant place matches about as well
  // (identical aisles, look-alike rooms) is ambiguous across the map, whatever its score.
  MatchRefusal why = MatchRefusal::kLowScore;
  struct Matched {
    NodeId id;
    MatchResult match;
  };
  std::vector<Matched> matched;
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
    if (!match.ok || match.score < lc.min_score) continue;
    if (match.ambiguity > lc.max_ambiguity) {
      why = MatchRefusal::kAmbiguous;
      continue;
    }
    if (!LocallyUnique(match, cur.points)) {
      why = MatchRefusal::kNotUnique;
      continue;
    }
    const auto reach = projected.find(p.id);
    if (reach != projected.end()) {
      // Where the uncertainty is small, a place far from the estimate is another place that
      // looks alike (the next aisle), not drift.
      Eigen::Vector3d correction = T2V(match.T_ref_cur) - T2V(values.at(current));
      correction.z() = NormalizeAngle(correction.z());
      const double k2 = g.plausible_sigmas * g.plausible_sigmas;
      const Eigen::Matrix3d S = k2 * reach->second.covariance + match.covariance;
      if (correction.dot(S.inverse() * correction) > lc.consistency_chi2) {
        why = MatchRefusal::kImplausible;
        continue;
      }
    }
    matched.push_back({p.id, match});
  }
  if (matched.empty()) {
    loop_state.verifier.NoteRefused(why);
    return false;
  }
  const auto best = std::max_element(
      matched.begin(), matched.end(),
      [](const Matched& a, const Matched& b) { return a.match.score < b.match.score; });
  for (const Matched& m : matched) {
    const double apart = std::hypot(m.match.T_ref_cur.x - best->match.T_ref_cur.x,
                                    m.match.T_ref_cur.y - best->match.T_ref_cur.y);
    if (apart > g.linear_window_m && m.match.score > lc.max_ambiguity * best->match.score) {
      loop_state.verifier.NoteRefused(MatchRefusal::kAmbiguous);
      return false;
    }
  }
  const Pose2& X_old = values.at(best->id);
  const MatchResult pair = RefineAgainstNode(best->id, cur.points, best->match);
  LoopHypothesis h;
  h.old = best->id;
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

}  // namespace lifelong::slam
