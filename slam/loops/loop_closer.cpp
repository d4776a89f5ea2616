// The local loop search (seed §4.3) and what both searches share: the submap match, its
// tests, and the proposal to the verifier. See loop_closer.hpp.
#include "slam/loops/loop_closer.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include <Eigen/LU>

#include "slam/graph/se2.hpp"
#include "slam/loops/approach_check.hpp"

namespace lifelong::slam {
namespace {

struct Candidate {
  NodeId id;
  double mahalanobis;
  Eigen::Matrix3d covariance;
};

const Candidate& Likeliest(const std::vector<Candidate>& candidates) {
  return *std::min_element(
      candidates.begin(), candidates.end(),
      [](const Candidate& a, const Candidate& b) { return a.mahalanobis < b.mahalanobis; });
}

// The candidates inside the gate: not near the current node along the graph, and within
// gate_chi2 of its position under their projected covariance plus the sensor overlap. Unless
// `wide`, a node whose 3-sigma region exceeds the largest window is none (a clamped window
// covers only part of where it may be, at the largest window's cost); *beyond counts those.
std::vector<Candidate> Gate(const LoopClosingView& view, NodeId current,
                            const std::map<NodeId, ProjectedNode>& projected,
                            const std::map<NodeId, double>& near, const LoopClosingConfig& lc,
                            bool wide, int* beyond) {
  const Pose2& X_cur = view.values.at(current);
  std::vector<Candidate> out;
  for (const auto& [id, node] : projected) {
    if (near.count(id)) continue;
    const Pose2& X = view.values.at(id);
    const Eigen::Vector2d d(X.x - X_cur.x, X.y - X_cur.y);
    const Eigen::Matrix2d S = node.covariance.block<2, 2>(0, 0) + lc.overlap_radius_m *
                                                                      lc.overlap_radius_m *
                                                                      Eigen::Matrix2d::Identity();
    const double m = d.dot(S.inverse() * d);
    if (m > lc.gate_chi2) continue;
    const double variance = std::max(node.covariance(0, 0), node.covariance(1, 1));
    if (!wide && 3.0 * std::sqrt(std::max(variance, 0.0)) > lc.max_window_m) {
      ++*beyond;
      continue;
    }
    out.push_back({id, m, node.covariance});
  }
  return out;
}

/// Keeps the candidates observed within `span` observations of the most likely one.
void KeepOneVisit(int span, std::vector<Candidate>* candidates) {
  const NodeId centre = Likeliest(*candidates).id;
  candidates->erase(
      std::remove_if(candidates->begin(), candidates->end(),
                     [&](const Candidate& c) { return std::abs(c.id - centre) > span; }),
      candidates->end());
}

/// A local search's submap and the largest variances of its candidates (the window).
struct Submap {
  std::set<NodeId> nodes;
  double var_x = 0.0, var_y = 0.0, var_th = 0.0;
};

/// Every candidate plus its graph neighbours that are not near the current node (and, with
/// submap_span, within that span of a candidate).
Submap BuildSubmap(const PoseGraph& graph, const std::vector<Candidate>& candidates,
                   const std::map<NodeId, double>& near, const LoopClosingConfig& lc) {
  const auto in_span = [&](NodeId n) {
    return lc.submap_span <= 0 ||
           std::any_of(candidates.begin(), candidates.end(),
                       [&](const Candidate& c) { return std::abs(n - c.id) <= lc.submap_span; });
  };
  Submap out;
  for (const Candidate& c : candidates) {
    out.nodes.insert(c.id);
    int added = 0;
    for (NodeId n : graph.Neighbours(c.id)) {
      if (added >= lc.neighbours_per_candidate) break;
      if (!near.count(n) && in_span(n)) {
        out.nodes.insert(n);
        ++added;
      }
    }
    out.var_x = std::max(out.var_x, c.covariance(0, 0));
    out.var_y = std::max(out.var_y, c.covariance(1, 1));
    out.var_th = std::max(out.var_th, c.covariance(2, 2));
  }
  return out;
}

/// The candidate nearest to the matched pose: the node the closure is attached to.
NodeId NearestCandidate(const Values& values, const std::vector<Candidate>& candidates,
                        const Pose2& matched) {
  NodeId old = candidates.front().id;
  double best_d = 1e300;
  for (const Candidate& c : candidates) {
    const Pose2& X = values.at(c.id);
    const double d = std::hypot(X.x - matched.x, X.y - matched.y);
    if (d < best_d) {
      best_d = d;
      old = c.id;
    }
  }
  return old;
}

}  // namespace

double LoopCloser::Clamp3Sigma(double variance, double lo, double hi) {
  return std::clamp(3.0 * std::sqrt(std::max(variance, 0.0)), lo, hi);
}

LoopCloser::LoopCloser(const LoopClosingConfig& loops, const IncrementalConfig& incremental)
    : config_(loops), incremental_(incremental), verifier_(loops.verify) {}

void LoopCloser::ForgetNode(NodeId id) {
  verifier_.ForgetNode(id);
  surfaces_.Erase(id);
  places_.Remove(id);
  reach_.Forget(id);
}

std::optional<LoopAttempt> LoopCloser::SearchLocal(const LoopClosingView& view, NodeId current,
                                                   int observation,
                                                   std::vector<LoopHypothesis>* accepted) {
  const LoopClosingConfig& lc = config_;
  ProjectionConfig projection;
  projection.max_position_sigma_m = lc.max_position_sigma_m;
  projected_ = ProjectCovariances(view.graph, view.values, current, projection, &groups_);
  const auto near = ExpandByPathLength(view.graph, view.values, current, lc.min_path_separation_m);
  int beyond = 0;
  // Wide at every n-th observation, and at every one while hypotheses wait for the others
  // that would confirm them (group verification needs several in a row).
  const bool wide = lc.beyond_window_every > 0 &&
                    (observation % lc.beyond_window_every == 0 || !verifier_.pending().empty());
  std::vector<Candidate> candidates = Gate(view, current, projected_, near, lc, wide, &beyond);
  if (candidates.empty()) {
    if (beyond > 0) verifier_.NoteBeyondWindow();
    return std::nullopt;
  }
  verifier_.NoteAttempt();
  LoopAttempt attempt;
  attempt.search = LoopAttempt::Search::kLocal;
  attempt.current = current;
  const auto refuse = [&](MatchRefusal why) {
    verifier_.NoteRefused(why);
    attempt.refused = why;
    return attempt;
  };
  // One traversal only: the candidates observed within submap_span observations of the most
  // likely one. Candidates of different visits disagree by whatever error the map still
  // holds between them; a submap mixing them is blurred, and a closure attached to one node
  // after matching against another visit's walls is off by that disagreement.
  if (lc.submap_span > 0) KeepOneVisit(lc.submap_span, &candidates);
  const Submap submap = BuildSubmap(view.graph, candidates, near, lc);
  attempt.candidates = static_cast<int>(candidates.size());
  attempt.old = Likeliest(candidates).id;
  MatcherConfig mc = lc.matcher;
  mc.linear_window_m = std::max(Clamp3Sigma(submap.var_x, lc.min_window_m, lc.max_window_m),
                                Clamp3Sigma(submap.var_y, lc.min_window_m, lc.max_window_m));
  mc.angular_window_rad = Clamp3Sigma(submap.var_th, lc.min_window_rad, lc.max_window_rad);
  attempt.window_m = mc.linear_window_m;
  attempt.window_rad = mc.angular_window_rad;
  MatchRefusal why = MatchRefusal::kLowScore;
  const Pose2& X_cur = view.values.at(current);
  const std::optional<MatchResult> found =
      MatchSubmap(view, submap.nodes, current, X_cur, mc, &why, &attempt.measured);
  if (!found) return refuse(why);
  const MatchResult& match = *found;

  // The correction must be plausible under the projected uncertainty of the best candidate.
  if (!Plausible(view, match, current, Likeliest(candidates).covariance)) {
    return refuse(MatchRefusal::kImplausible);
  }
  const NodeId old = NearestCandidate(view.values, candidates, match.T_ref_cur);
  attempt.old = old;
  attempt.proposed = true;
  attempt.accepted = Propose(view, old, current, match, accepted);
  return attempt;
}

std::optional<MatchResult> LoopCloser::MatchSubmap(const LoopClosingView& view,
                                                   const std::set<NodeId>& submap, NodeId current,
                                                   const Pose2& guess, const MatcherConfig& mc,
                                                   MatchRefusal* why, MatchMeasure* measured,
                                                   const std::vector<Eigen::Vector2d>* query) {
  const LoopClosingConfig& lc = config_;
  const std::vector<Eigen::Vector2d>& points =
      query != nullptr ? *query : view.nodes.at(current).points;
  std::vector<Eigen::Vector2d> reference;
  for (NodeId id : submap) {
    const std::vector<Eigen::Vector2d> pts = Reference(view, id);
    reference.insert(reference.end(), pts.begin(), pts.end());
  }
  CropToSearch(points, guess, mc, &reference);
  if (static_cast<int>(reference.size()) < lc.min_reference_points) {
    *why = MatchRefusal::kFewPoints;
    return std::nullopt;
  }
  grid_.Build(reference, mc);
  const MatchResult match = Match(grid_, points, guess, Cutting(mc));
  measured->score = match.score;
  measured->ambiguity = match.ambiguity;
  if (!match.ok || match.score < lc.min_score) {
    *why = MatchRefusal::kLowScore;
  } else if (match.ambiguity > lc.max_ambiguity) {
    *why = MatchRefusal::kAmbiguous;
  } else if (!LocallyUnique(match, points)) {
    *why = MatchRefusal::kNotUnique;
  } else if (match.ambiguity >= lc.context_ambiguity &&
             !ApproachAgrees(view, current, match.T_ref_cur, match.T_ref_rival, lc, &reach_,
                             &approach_grid_)) {
    *why = MatchRefusal::kApproachDisagrees;
  } else {
    return match;
  }
  return std::nullopt;
}

bool LoopCloser::Plausible(const LoopClosingView& view, const MatchResult& match, NodeId current,
                           const Eigen::Matrix3d& covariance) const {
  Eigen::Vector3d correction = T2V(match.T_ref_cur) - T2V(view.values.at(current));
  correction.z() = NormalizeAngle(correction.z());
  const Eigen::Matrix3d S = covariance + match.covariance;
  return correction.dot(S.inverse() * correction) <= config_.consistency_chi2;
}

int LoopCloser::Propose(const LoopClosingView& view, NodeId old, NodeId current,
                        const MatchResult& match, std::vector<LoopHypothesis>* accepted) {
  const NodeData& cur = view.nodes.at(current);
  const MatchResult pair = RefineAgainstNode(view, old, cur.points, match);
  LoopHypothesis h;
  h.old = old;
  h.current = current;
  h.T_old_current = Between(view.values.at(old), pair.T_ref_cur);
  h.information = RotateIntoFrame(pair.information, pair.T_ref_cur.theta);
  h.covariance = h.information.inverse();
  h.travelled_m = cur.travelled_m;
  if (hook_) hook_(&h, view.values);
  const std::vector<LoopHypothesis> now = verifier_.Add(h, view.values);
  accepted->insert(accepted->end(), now.begin(), now.end());
  return static_cast<int>(now.size());
}

std::vector<Eigen::Vector2d> LoopCloser::Reference(const LoopClosingView& view, NodeId id) {
  const bool surfaces = config_.surfaces && incremental_.surfaces.JoinsAny();
  const NodeData& node = view.nodes.at(id);
  if (!surfaces) return ToWorld(node.points, view.values.at(id));
  const auto make = [&] {
    SurfaceRule rule = incremental_.surfaces;
    if (!config_.surface_lines) rule.line_gap_m = 0.0;
    return ScanSurfaces(node.scan, incremental_, rule);
  };
  return ToWorld(surfaces_.Get(id, make), view.values.at(id));
}

MatchResult LoopCloser::RefineAgainstNode(const LoopClosingView& view, NodeId old,
                                          const std::vector<Eigen::Vector2d>& points,
                                          const MatchResult& submap_match) {
  const LoopClosingConfig& lc = config_;
  if (lc.refine_window_m <= 0.0) return submap_match;
  // The submap holds several nodes whose estimates may disagree by what the map still gets
  // wrong; the edge goes to `old` alone, so it is measured against old's scan alone,
  // in a narrow window around the submap's answer.
  std::vector<Eigen::Vector2d> reference = Reference(view, old);
  MatcherConfig mc = lc.matcher;
  mc.linear_window_m = lc.refine_window_m;
  mc.angular_window_rad = lc.refine_window_rad;
  CropToSearch(points, submap_match.T_ref_cur, mc, &reference);
  if (static_cast<int>(reference.size()) < lc.min_reference_points / 2) return submap_match;
  grid_.Build(reference, mc);
  const MatchResult pair = Match(grid_, points, submap_match.T_ref_cur, Cutting(mc));
  return pair.ok && pair.score >= lc.min_score ? pair : submap_match;
}

MatcherConfig LoopCloser::Cutting(MatcherConfig mc) const {
  // Nothing below loops.min_score is accepted, so the search need not look below it.
  mc.min_score = std::max(mc.min_score, config_.min_score);
  mc.cut_below_min_score = !config_.measure_low_scores;
  return mc;
}

bool LoopCloser::LocallyUnique(const MatchResult& match,
                               const std::vector<Eigen::Vector2d>& points) const {
  const LoopClosingConfig& lc = config_;
  if (lc.max_flatness >= 1.0 || match.score <= 0.0) return true;
  // A corridor or an aisle scores almost as well a little further along its axis: the
  // best pose there is one of many, and its error along the axis is unobserved.
  const Pose2& best = match.T_ref_cur;
  for (int k = 0; k < 8; ++k) {
    const double a = k * M_PI / 4.0;
    const Pose2 shifted(best.x + lc.uniqueness_radius_m * std::cos(a),
                        best.y + lc.uniqueness_radius_m * std::sin(a), best.theta);
    if (ScoreAt(grid_, points, shifted) > lc.max_flatness * match.score) return false;
  }
  return true;
}

}  // namespace lifelong::slam
