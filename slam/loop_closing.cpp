// Loop closing (seed §4.3): candidates are the nodes inside the current pose's uncertainty,
// found by Dijkstra projection of covariances; the current scan is matched with a wide window
// against a submap of the candidates' scans, and accepted only when the match is good,
// unambiguous and consistent with the projected uncertainty.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include <Eigen/LU>

#include "slam/dijkstra.hpp"
#include "slam/mapper_state.hpp"
#include "slam/scan_matcher.hpp"
#include "slam/se2.hpp"

namespace lifelong::slam {
namespace {

struct Candidate {
  NodeId id;
  double mahalanobis;
  Eigen::Matrix3d covariance;
};

double Clamp3Sigma(double variance, double lo, double hi) {
  return std::clamp(3.0 * std::sqrt(std::max(variance, 0.0)), lo, hi);
}

}  // namespace

std::map<NodeId, ProjectedNode> Mapper::State::ProjectFrom(NodeId current) const {
  ProjectionConfig projection;
  projection.max_position_sigma_m = config.loops.max_position_sigma_m;
  return ProjectCovariances(graph, values, current, projection);
}

std::optional<MatchResult> Mapper::State::MatchSubmap(const std::set<NodeId>& submap,
                                                      NodeId current, const Pose2& guess,
                                                      const MatcherConfig& mc, MatchRefusal* why) {
  const LoopClosingConfig& lc = config.loops;
  const std::vector<Eigen::Vector2d>& points = nodes.at(current).points;
  std::vector<Eigen::Vector2d> reference;
  for (NodeId id : submap) {
    const std::vector<Eigen::Vector2d> pts = LoopReference(id);
    reference.insert(reference.end(), pts.begin(), pts.end());
  }
  CropToSearch(points, guess, mc, &reference);
  if (static_cast<int>(reference.size()) < lc.min_reference_points) {
    *why = MatchRefusal::kFewPoints;
    return std::nullopt;
  }
  match_grid.Build(reference, mc);
  const MatchResult match = Match(match_grid, points, guess, mc);
  if (!match.ok || match.score < lc.min_score) {
    *why = MatchRefusal::kLowScore;
  } else if (match.ambiguity > lc.max_ambiguity) {
    *why = MatchRefusal::kAmbiguous;
  } else if (!LocallyUnique(match, points)) {
    *why = MatchRefusal::kNotUnique;
  } else {
    return match;
  }
  return std::nullopt;
}

bool Mapper::State::Plausible(const MatchResult& match, NodeId current,
                              const Eigen::Matrix3d& covariance) const {
  Eigen::Vector3d correction = T2V(match.T_ref_cur) - T2V(values.at(current));
  correction.z() = NormalizeAngle(correction.z());
  const Eigen::Matrix3d S = covariance + match.covariance;
  return correction.dot(S.inverse() * correction) <= config.loops.consistency_chi2;
}

bool Mapper::State::ProposeClosure(NodeId old, NodeId current, const MatchResult& match) {
  const MatchResult pair = RefineAgainstNode(old, nodes.at(current).points, match);
  LoopHypothesis h;
  h.old = old;
  h.current = current;
  h.T_old_current = Between(values.at(old), pair.T_ref_cur);
  h.information = RotateIntoFrame(pair.information, pair.T_ref_cur.theta);
  h.covariance = h.information.inverse();
  h.travelled_m = nodes.at(current).travelled_m;
  MaybeInjectFalse(&h);
  bool closed = false;
  for (const LoopHypothesis& accepted : loop_state.verifier.Add(h, values)) {
    AddLoopEdge(accepted);
    closed = true;
  }
  return closed;
}

bool Mapper::State::TryCloseLoop(NodeId current, const std::map<NodeId, ProjectedNode>& projected) {
  const LoopClosingConfig& lc = config.loops;
  const auto near = ExpandByPathLength(graph, values, current, lc.min_path_separation_m);
  const Pose2& X_cur = values.at(current);

  std::vector<Candidate> candidates;
  for (const auto& [id, node] : projected) {
    if (near.count(id)) continue;
    const Pose2& X = values.at(id);
    const Eigen::Vector2d d(X.x - X_cur.x, X.y - X_cur.y);
    const Eigen::Matrix2d S = node.covariance.block<2, 2>(0, 0) + lc.overlap_radius_m *
                                                                      lc.overlap_radius_m *
                                                                      Eigen::Matrix2d::Identity();
    const double m = d.dot(S.inverse() * d);
    if (m <= lc.gate_chi2) candidates.push_back({id, m, node.covariance});
  }
  if (candidates.empty()) return false;
  loop_state.verifier.NoteAttempt();
  const auto refuse = [this](MatchRefusal why) {
    loop_state.verifier.NoteRefused(why);
    return false;
  };
  // One traversal only: the candidates observed within submap_span observations of the most
  // likely one. Candidates of different visits disagree by whatever error the map still
  // holds between them; a submap mixing them is blurred, and a closure attached to one node
  // after matching against another visit's walls is off by that disagreement.
  if (lc.submap_span > 0) {
    const NodeId centre = std::min_element(candidates.begin(), candidates.end(),
                                           [](const Candidate& a, const Candidate& b) {
                                             return a.mahalanobis < b.mahalanobis;
                                           })
                              ->id;
    candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                    [&](const Candidate& c) {
                                      return std::abs(c.id - centre) > lc.submap_span;
                                    }),
                     candidates.end());
  }
  const auto in_span = [&](NodeId n) {
    return lc.submap_span <= 0 ||
           std::any_of(candidates.begin(), candidates.end(),
                       [&](const Candidate& c) { return std::abs(n - c.id) <= lc.submap_span; });
  };

  // The submap: every candidate plus its graph neighbours that are not near the current node.
  std::set<NodeId> submap;
  double var_x = 0.0, var_y = 0.0, var_th = 0.0;
  for (const Candidate& c : candidates) {
    submap.insert(c.id);
    int added = 0;
    for (NodeId n : graph.Neighbours(c.id)) {
      if (added >= lc.neighbours_per_candidate) break;
      if (!near.count(n) && in_span(n)) {
        submap.insert(n);
        ++added;
      }
    }
    var_x = std::max(var_x, c.covariance(0, 0));
    var_y = std::max(var_y, c.covariance(1, 1));
    var_th = std::max(var_th, c.covariance(2, 2));
  }
  MatcherConfig mc = lc.matcher;
  mc.linear_window_m = std::max(Clamp3Sigma(var_x, lc.min_window_m, lc.max_window_m),
                                Clamp3Sigma(var_y, lc.min_window_m, lc.max_window_m));
  mc.angular_window_rad = Clamp3Sigma(var_th, lc.min_window_rad, lc.max_window_rad);
  MatchRefusal why = MatchRefusal::kLowScore;
  const std::optional<MatchResult> found = MatchSubmap(submap, current, X_cur, mc, &why);
  if (!found) return refuse(why);
  const MatchResult& match = *found;

  // The correction must be plausible under the projected uncertainty of the best candidate.
  const auto best = std::min_element(
      candidates.begin(), candidates.end(),
      [](const Candidate& a, const Candidate& b) { return a.mahalanobis < b.mahalanobis; });
  if (!Plausible(match, current, best->covariance)) return refuse(MatchRefusal::kImplausible);

  // Attach the closure to the candidate nearest to the matched pose.
  NodeId old = candidates.front().id;
  double best_d = 1e300;
  for (const Candidate& c : candidates) {
    const Pose2& X = values.at(c.id);
    const double d = std::hypot(X.x - match.T_ref_cur.x, X.y - match.T_ref_cur.y);
    if (d < best_d) {
      best_d = d;
      old = c.id;
    }
  }
  return ProposeClosure(old, current, match);
}

std::vector<Eigen::Vector2d> Mapper::State::LoopReference(NodeId id) {
  const bool surfaces = config.loops.surfaces && config.incremental.surfaces.JoinsAny();
  if (!surfaces) return ToWorld(nodes.at(id).points, values.at(id));
  const auto make = [&] {
    SurfaceRule rule = config.incremental.surfaces;
    if (!config.loops.surface_lines) rule.line_gap_m = 0.0;
    return SurfacesOf(id, rule);
  };
  return ToWorld(loop_surfaces.Get(id, make), values.at(id));
}

MatchResult Mapper::State::RefineAgainstNode(NodeId old, const std::vector<Eigen::Vector2d>& points,
                                             const MatchResult& submap_match) {
  const LoopClosingConfig& lc = config.loops;
  if (lc.refine_window_m <= 0.0) return submap_match;
  // The submap holds several nodes whose estimates may disagree by what the map still gets
  // wrong; the edge goes to `old` alone, so it is measured against old's scan alone,
  // in a narrow window around the submap's answer.
  std::vector<Eigen::Vector2d> reference = LoopReference(old);
  MatcherConfig mc = lc.matcher;
  mc.linear_window_m = lc.refine_window_m;
  mc.angular_window_rad = lc.refine_window_rad;
  CropToSearch(points, submap_match.T_ref_cur, mc, &reference);
  if (static_cast<int>(reference.size()) < lc.min_reference_points / 2) return submap_match;
  match_grid.Build(reference, mc);
  const MatchResult pair = Match(match_grid, points, submap_match.T_ref_cur, mc);
  return pair.ok && pair.score >= lc.min_score ? pair : submap_match;
}

bool Mapper::State::LocallyUnique(const MatchResult& match,
                                  const std::vector<Eigen::Vector2d>& points) const {
  const LoopClosingConfig& lc = config.loops;
  if (lc.max_flatness >= 1.0 || match.score <= 0.0) return true;
  // A corridor or an aisle scores almost as well a little further along its axis: the
  // best pose there is one of many, and its error along the axis is unobserved.
  const Pose2& best = match.T_ref_cur;
  for (int k = 0; k < 8; ++k) {
    const double a = k * M_PI / 4.0;
    const Pose2 shifted(best.x + lc.uniqueness_radius_m * std::cos(a),
                        best.y + lc.uniqueness_radius_m * std::sin(a), best.theta);
    if (ScoreAt(match_grid, points, shifted) > lc.max_flatness * match.score) return false;
  }
  return true;
}

void Mapper::State::MaybeInjectFalse(LoopHypothesis* h) {
  const LoopClosingConfig& lc = config.loops;
  const int n = loop_state.hypotheses++;
  if (lc.inject_false_share <= 0.0) return;
  // Every 1/share-th hypothesis, deterministically: when floor(k * share) steps up.
  if (std::floor((n + 1) * lc.inject_false_share) == std::floor(n * lc.inject_false_share)) {
    return;
  }
  const Pose2 matched = values.at(h->old) * h->T_old_current;
  const Pose2 moved(matched.x + lc.inject_false_dx_m, matched.y + lc.inject_false_dy_m,
                    matched.theta);
  h->T_old_current = Between(values.at(h->old), moved);
  h->injected = true;
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
  loop_state.loops.push_back(
      {h.current, h.old, scans[static_cast<std::size_t>(nodes.at(h.current).scan_index)].stamp_s,
       scans[static_cast<std::size_t>(nodes.at(h.old).scan_index)].stamp_s, edge.T_from_to,
       h.injected});
  ++loop_state.since_optimize;
  ++loop_state.since_sync;
  const Eigen::Vector3d e = RelativeError(values.at(h.old), values.at(h.current), edge.T_from_to);
  if (e.dot(edge.information * e) > lc.optimize_edge_chi2 ||
      loop_state.since_sync >= lc.optimize_every) {
    OptimizeAndSyncMap();
  }
}

std::vector<std::optional<double>> Mapper::LoopEdgeChi2() const {
  const State& s = *state_;
  std::map<std::pair<NodeId, NodeId>, double> chi2;  // (old, current) -> chi2
  for (const PoseEdge& edge : s.graph.edges()) {
    if (edge.kind != EdgeKind::kLoop) continue;
    const Eigen::Vector3d e =
        RelativeError(s.values.at(edge.from), s.values.at(edge.to), edge.T_from_to);
    chi2[{edge.from, edge.to}] = e.dot(edge.information * e);
  }
  std::vector<std::optional<double>> out;
  out.reserve(s.loop_state.loops.size());
  for (const LoopClosureRecord& r : s.loop_state.loops) {
    const auto it = chi2.find({r.old, r.current});
    out.push_back(it == chi2.end() ? std::nullopt : std::optional<double>(it->second));
  }
  return out;
}

std::set<NodeId> Mapper::State::UnsettledNodes() const {
  std::set<NodeId> out;
  for (const LoopHypothesis& h : loop_state.verifier.pending()) {
    out.insert(h.old);
    out.insert(h.current);
  }
  for (const PoseEdge& edge : graph.edges()) {
    if (edge.kind != EdgeKind::kLoop) continue;
    const auto a = values.find(edge.from), b = values.find(edge.to);
    if (a == values.end() || b == values.end()) continue;
    const Eigen::Vector3d e = RelativeError(a->second, b->second, edge.T_from_to);
    if (e.dot(edge.information * e) > config.loops.suspect_chi2) {
      out.insert(edge.from);
      out.insert(edge.to);
    }
  }
  return out;
}

}  // namespace lifelong::slam
