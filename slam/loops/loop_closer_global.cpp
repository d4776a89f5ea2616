// The global loop search (loops.global; loop_config.hpp GlobalLoopConfig): candidates come
// from the place index, not from the projected uncertainty, so a revisit is found however far
// the estimate has drifted. The query is described from the robot and from origins beside
// it (loops.global.lateral_steps), for a polar descriptor changes with a lane's offset. Each
// candidate is matched by the correlative matcher's branch and bound in a window of
// loops.global.linear_window_m around the candidate node's position, at the heading the
// descriptors agree on, against the candidate and its graph neighbours. Where the scan scores
// too low there, its near returns alone (loops.global.near_range_m) are matched again against
// the scans of the candidate's whole visit (submap_travel_m): a place driven the other way. A
// match must pass the local search's tests (score, ambiguity, local uniqueness). The test against
// the projected uncertainty is widened (plausible_sigmas) where the projection reaches the
// candidate and left out where it does not, since the drift is what is being corrected; and
// no other proposal far from the best may score nearly as well (cross-map ambiguity). Then
// it goes through the same group verification (slam/loops/loop_verifier.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <vector>

#include "slam/graph/se2.hpp"
#include "slam/loops/loop_closer.hpp"
#include "slam/matching/scan_matcher.hpp"

namespace lifelong::slam {
namespace {

// The old scans a candidate is matched against: the candidate and its first graph
// neighbours.
std::set<NodeId> CandidateSubmap(const LoopClosingView& view, NodeId candidate,
                                 const LoopClosingConfig& lc) {
  std::set<NodeId> submap{candidate};
  int added = 0;
  for (NodeId n : view.graph.Neighbours(candidate)) {
    if (added++ >= lc.neighbours_per_candidate) break;
    submap.insert(n);
  }
  return submap;
}

// ...and for the near returns' second match, with them the old nodes within
// loops.global.submap_travel_m of odometry travel of the candidate (its visit). Nodes less than
// min_path_separation_m of travel back from the current one are left out, as they are for
// candidates.
std::set<NodeId> VisitSubmap(const LoopClosingView& view, NodeId candidate, NodeId current,
                             const LoopClosingConfig& lc) {
  std::set<NodeId> submap = CandidateSubmap(view, candidate, lc);
  const double span_m = lc.global.submap_travel_m;
  const double at_m = view.nodes.at(candidate).travelled_m;
  const double recent_m = view.nodes.at(current).travelled_m - lc.min_path_separation_m;
  for (const auto& [id, node] : view.nodes) {
    if (std::abs(node.travelled_m - at_m) <= span_m && node.travelled_m <= recent_m) {
      submap.insert(id);
    }
  }
  return submap;
}

}  // namespace

std::vector<Eigen::Vector2d> LoopCloser::NearReturns(const std::vector<Eigen::Vector2d>& points,
                                                     const GlobalLoopConfig& g) {
  std::vector<Eigen::Vector2d> near;
  if (g.near_range_m <= 0.0) return near;
  for (const Eigen::Vector2d& p : points) {
    if (p.norm() <= g.near_range_m) near.push_back(p);
  }
  return near;
}

std::optional<LoopAttempt> LoopCloser::SearchGlobal(const LoopClosingView& view, NodeId current,
                                                    bool search,
                                                    std::vector<LoopHypothesis>* accepted) {
  const GlobalLoopConfig& g = config_.global;
  if (!g.enabled) return std::nullopt;
  const std::vector<Eigen::Vector2d> points = PlacePoints(view, current);
  const PlaceDescriptor place = DescribePlace(points, g.descriptor);
  std::optional<LoopAttempt> attempt;
  // While a closure by place waits for confirmation, it is followed instead of searching
  // (the follow-up matches the scan, not the place: a sparse place does not stop it).
  if (following_) attempt = Follow(view, current, accepted);
  if (place.occupied < g.min_occupied) return attempt;
  if (!following_ && search && !attempt) {
    verifier_.NoteGlobalSearch();
    attempt = MatchPlaces(view, current, points, place, accepted);
  }
  // Indexed after its own search, so that it never finds itself.
  places_.Add(current, place);
  return attempt;
}

std::vector<Eigen::Vector2d> LoopCloser::PlacePoints(const LoopClosingView& view, NodeId id) const {
  const GlobalLoopConfig& g = config_.global;
  const Pose2& X = view.values.at(id);
  const std::vector<NodeId>& recent = view.recent;
  std::vector<Eigen::Vector2d> points;
  const auto count = static_cast<std::ptrdiff_t>(std::max(g.context_nodes, 0) + 1);
  const auto it = std::find(recent.begin(), recent.end(), id);
  const auto last = it == recent.end() ? recent.end() : std::next(it);
  const auto first = last - std::min(count, last - recent.begin());
  for (auto n = first; n != last; ++n) {
    const Pose2 T_id_n = Between(X, view.values.at(*n));
    for (const Eigen::Vector2d& p : view.nodes.at(*n).points) {
      double x = 0.0, y = 0.0;
      T_id_n.Apply(p.x(), p.y(), &x, &y);
      points.emplace_back(x, y);
    }
  }
  return points;
}

std::vector<LoopCloser::PlaceCandidate> LoopCloser::SimilarPlaces(
    const LoopClosingView& view, NodeId current, const std::vector<Eigen::Vector2d>& points,
    const PlaceDescriptor& place) const {
  const GlobalLoopConfig& g = config_.global;
  const NodeData& cur = view.nodes.at(current);
  std::map<NodeId, PlaceCandidate> best;  // per place, its most similar query
  const auto compare = [&](const PlaceDescriptor& query, double lateral_m) {
    if (query.occupied < g.min_occupied) return;
    for (NodeId id : places_.Nearest(query, static_cast<std::size_t>(g.index_neighbours))) {
      const auto node = view.nodes.find(id);
      if (node == view.nodes.end()) continue;
      // Not a revisit: the robot has not left this place (odometry path length).
      if (cur.travelled_m - node->second.travelled_m < config_.min_path_separation_m) continue;
      const PlaceComparison cmp = ComparePlaces(query, places_.Get(id));
      if (cmp.distance > g.max_distance) continue;
      const auto it = best.find(id);
      if (it == best.end() || cmp.distance < it->second.cmp.distance) {
        const Pose2 guess =
            view.values.at(id) * Pose2(0.0, 0.0, cmp.yaw_rad) * Pose2(0.0, -lateral_m, 0.0);
        best[id] = {id, cmp, lateral_m, guess, {}};
      }
    }
  };
  compare(place, 0.0);
  // Scan Context's bins are polar: a street driven a lane or two to the side puts the near
  // walls in other sectors and rings. The query described from origins beside the robot
  // finds such a place again (Kim et al. 2021, Scan Context++, its lateral augmentation).
  for (int k = 1; k <= g.lateral_steps; ++k) {
    for (const double side : {-1.0, 1.0}) {
      const double lateral_m = side * k * g.lateral_step_m;
      std::vector<Eigen::Vector2d> shifted = points;
      for (Eigen::Vector2d& p : shifted) p.y() -= lateral_m;
      compare(DescribePlace(shifted, g.descriptor), lateral_m);
    }
  }
  std::vector<PlaceCandidate> out;
  for (const auto& [id, c] : best) out.push_back(c);
  std::sort(out.begin(), out.end(), [](const PlaceCandidate& a, const PlaceCandidate& b) {
    return a.cmp.distance < b.cmp.distance;
  });
  if (static_cast<int>(out.size()) > g.candidates) out.resize(g.candidates);
  return out;
}

std::vector<LoopCloser::PlaceCandidate> LoopCloser::MatchCandidates(
    const LoopClosingView& view, NodeId current, const std::vector<Eigen::Vector2d>* near,
    const std::vector<PlaceCandidate>& candidates, const MatcherConfig& mc, MatchRefusal* why,
    LoopAttempt* attempt) {
  const double k2 = config_.global.plausible_sigmas * config_.global.plausible_sigmas;
  std::vector<PlaceCandidate> matched;
  // The most similar place, unless one is measured (a search cut at min_score measures none).
  if (!candidates.empty()) attempt->old = candidates.front().id;
  for (const PlaceCandidate& p : candidates) {
    const Pose2& guess = p.guess;
    MatchRefusal refused = MatchRefusal::kLowScore;
    MatchMeasure measured;
    std::optional<MatchResult> match = MatchSubmap(view, CandidateSubmap(view, p.id, config_),
                                                   current, guess, mc, &refused, &measured);
    const bool weak = refused == MatchRefusal::kLowScore || refused == MatchRefusal::kFewPoints;
    if (!match && weak && near != nullptr) {
      // A place driven the other way: the near returns against the scans of its visit.
      MatchMeasure again;
      match = MatchSubmap(view, VisitSubmap(view, p.id, current, config_), current, guess, mc,
                          &refused, &again, near);
      if (!std::isnan(again.score) &&
          (std::isnan(measured.score) || again.score > measured.score)) {
        measured = again;
      }
    }
    const double best = attempt->measured.score;
    if (!std::isnan(measured.score) && (std::isnan(best) || measured.score > best)) {
      attempt->measured = measured;
      attempt->old = p.id;
    }
    if (!match) {
      if (refused != MatchRefusal::kLowScore) *why = refused;
      continue;
    }
    // Where the covariance projection reaches the candidate, a place far outside its
    // uncertainty (inflated by plausible_sigmas) is another place that looks alike (the next
    // aisle), not drift; one it does not reach may be anywhere.
    const auto reach = projected_.find(p.id);
    if (reach != projected_.end() &&
        !Plausible(view, *match, current, k2 * reach->second.covariance)) {
      *why = MatchRefusal::kImplausible;
      continue;
    }
    matched.push_back({p.id, p.cmp, p.lateral_m, p.guess, *match});
  }
  return matched;
}

std::optional<LoopAttempt> LoopCloser::MatchPlaces(const LoopClosingView& view, NodeId current,
                                                   const std::vector<Eigen::Vector2d>& points,
                                                   const PlaceDescriptor& place,
                                                   std::vector<LoopHypothesis>* accepted) {
  const LoopClosingConfig& lc = config_;
  const GlobalLoopConfig& g = lc.global;
  const std::vector<PlaceCandidate> proposals = SimilarPlaces(view, current, points, place);
  if (proposals.empty()) return std::nullopt;
  verifier_.NoteGlobalAttempt();
  LoopAttempt attempt;
  attempt.search = LoopAttempt::Search::kGlobal;
  attempt.current = current;
  attempt.candidates = static_cast<int>(proposals.size());
  MatcherConfig mc = lc.matcher;
  mc.linear_window_m = attempt.window_m = g.linear_window_m;
  mc.angular_window_rad = attempt.window_rad = g.angular_window_rad;
  const auto refuse = [&](MatchRefusal why) {
    verifier_.NoteRefused(why);
    attempt.refused = why;
    return attempt;
  };
  // Every proposal is matched: a place that another, distant place matches about as well
  // (identical aisles, look-alike rooms) is ambiguous across the map, whatever its score.
  MatchRefusal why = MatchRefusal::kLowScore;
  const std::vector<Eigen::Vector2d> near = NearReturns(view.nodes.at(current).points, g);
  const std::vector<PlaceCandidate> matched =
      MatchCandidates(view, current, near.empty() ? nullptr : &near, proposals, mc, &why, &attempt);
  if (matched.empty()) return refuse(why);
  const auto best = std::max_element(matched.begin(), matched.end(),
                                     [](const PlaceCandidate& a, const PlaceCandidate& b) {
                                       return a.match.score < b.match.score;
                                     });
  for (const PlaceCandidate& m : matched) {
    const double apart = std::hypot(m.match.T_ref_cur.x - best->match.T_ref_cur.x,
                                    m.match.T_ref_cur.y - best->match.T_ref_cur.y);
    if (apart > g.linear_window_m && m.match.score > lc.max_ambiguity * best->match.score) {
      return refuse(MatchRefusal::kAmbiguous);
    }
  }
  verifier_.NoteGlobalProposed();
  attempt.old = best->id;
  attempt.measured = {best->match.score, best->match.ambiguity};
  attempt.proposed = true;
  attempt.accepted = Propose(view, best->id, current, best->match, accepted);
  // Following gives a place its confirmation without a second look by place: only a place
  // without a look-alike rival (the approach test's bar, loops.context_ambiguity) is followed.
  if (best->match.ambiguity < lc.context_ambiguity) StartFollowing(view, best->id, current);
  return attempt;
}

}  // namespace lifelong::slam
