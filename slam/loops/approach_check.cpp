// The approach test of a loop-closure match; see approach_check.hpp.
#include <algorithm>
#include <cmath>
#include <vector>

#include "slam/graph/se2.hpp"
#include "slam/loops/approach_check.hpp"

namespace lifelong::slam {
namespace {

/// The points of the nodes observed in the last `span_m` of travel before `current` (not
/// current's own), in current's frame.
std::vector<Eigen::Vector2d> ApproachPoints(const LoopClosingView& view, NodeId current,
                                            double span_m) {
  const Pose2& X = view.values.at(current);
  const double since = view.nodes.at(current).travelled_m - span_m;
  std::vector<Eigen::Vector2d> points;
  for (auto it = view.recent.rbegin(); it != view.recent.rend(); ++it) {
    if (*it == current) continue;
    const NodeData& node = view.nodes.at(*it);
    if (node.travelled_m < since) break;
    const std::vector<Eigen::Vector2d> in_current =
        ToWorld(node.points, Between(X, view.values.at(*it)));
    points.insert(points.end(), in_current.begin(), in_current.end());
  }
  return points;
}

}  // namespace

double NodeReach::Of(NodeId id, const NodeData& node) {
  const auto found = reach_.find(id);
  if (found != reach_.end()) return found->second;
  double squared = 0.0;
  for (const Eigen::Vector2d& p : node.points) squared = std::max(squared, p.squaredNorm());
  return reach_[id] = std::sqrt(squared);
}

bool ApproachAgrees(const LoopClosingView& view, NodeId current, const Pose2& match,
                    const Pose2& rival, const LoopClosingConfig& lc, NodeReach* reach,
                    ReferenceGrid* grid) {
  const std::vector<Eigen::Vector2d> approach = ApproachPoints(view, current, lc.context_span_m);
  if (approach.size() < 10) return true;  // no way in to judge by
  double span = 0.0;                      // how far from the poses the approach's points lie
  for (const Eigen::Vector2d& p : approach) span = std::max(span, p.norm());
  span += 1.0;
  // The older scans: nodes observed before the approach by more than the closing's path
  // separation, so that neither the approach nor the scans just before it vouch for
  // themselves. A node whose farthest point cannot reach either pose adds nothing; the
  // others' points are filtered one by one.
  const double before =
      view.nodes.at(current).travelled_m - lc.context_span_m - lc.min_path_separation_m;
  const Pose2 poses[2] = {match, rival};
  const auto within = [&](const Eigen::Vector2d& p, double r) {
    return std::any_of(std::begin(poses), std::end(poses),
                       [&](const Pose2& T) { return std::hypot(p.x() - T.x, p.y() - T.y) <= r; });
  };
  std::vector<Eigen::Vector2d> reference;
  for (const auto& [id, node] : view.nodes) {
    if (node.travelled_m >= before) continue;
    const Pose2& T = view.values.at(id);
    if (!within({T.x, T.y}, span + reach->Of(id, node))) continue;
    for (const Eigen::Vector2d& p : ToWorld(node.points, T)) {
      if (within(p, span)) reference.push_back(p);
    }
  }
  if (static_cast<int>(reference.size()) < lc.min_reference_points) return true;
  MatcherConfig mc = lc.matcher;
  mc.coarse_factor = 1;  // scores at two poses: the bound tables are not needed
  grid->Build(reference, mc);
  return ScoreAt(*grid, approach, match) >= ScoreAt(*grid, approach, rival);
}

}  // namespace lifelong::slam
