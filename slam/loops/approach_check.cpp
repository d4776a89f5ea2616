// The approach test of a loop-closure match; see approach_check.hpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>
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

/// Square buckets of side `side` around a set of points: a point in none of the 3 x 3
/// buckets around its own lies farther than `side` from every one of them.
class NearSet {
 public:
  explicit NearSet(double side) : side_(side) {}
  void Add(const Eigen::Vector2d& p) { keys_.insert(Key(Bucket(p.x()), Bucket(p.y()))); }
  bool Near(const Eigen::Vector2d& p) const {
    const std::int64_t bx = Bucket(p.x()), by = Bucket(p.y());
    for (std::int64_t dy = -1; dy <= 1; ++dy) {
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        if (keys_.count(Key(bx + dx, by + dy)) != 0) return true;
      }
    }
    return false;
  }

 private:
  std::int64_t Bucket(double v) const { return static_cast<std::int64_t>(std::floor(v / side_)); }
  static std::uint64_t Key(std::int64_t x, std::int64_t y) {
    return (static_cast<std::uint64_t>(x) << 32) ^ (static_cast<std::uint64_t>(y) & 0xffffffffu);
  }
  double side_;
  std::unordered_set<std::uint64_t> keys_;
};

}  // namespace

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
  // Only the field at the approach's points is read (ScoreAt: the value of the cell a point
  // falls in, made of the reference points within 3 sigma of the cell's centre), so a point
  // farther than that from all of them would change no score and is not rasterized.
  NearSet near(3.0 * lc.matcher.sigma_m + lc.matcher.resolution_m);
  for (const Pose2& T : poses) {
    for (const Eigen::Vector2d& p : ToWorld(approach, T)) near.Add(p);
  }
  std::vector<Eigen::Vector2d> reference;
  int within_span = 0;  // enough of them to judge by?
  for (const auto& [id, node] : view.nodes) {
    if (node.travelled_m >= before) continue;
    const Pose2& T = view.values.at(id);
    if (!within({T.x, T.y}, span + reach->Of(id, node))) continue;
    for (const Eigen::Vector2d& p : ToWorld(node.points, T)) {
      if (!within(p, span)) continue;
      ++within_span;
      if (near.Near(p)) reference.push_back(p);
    }
  }
  if (within_span < lc.min_reference_points) return true;
  MatcherConfig mc = lc.matcher;
  mc.coarse_factor = 1;  // scores at two poses: the bound tables are not needed
  grid->Build(reference, mc);
  return ScoreAt(*grid, approach, match) >= ScoreAt(*grid, approach, rival);
}

}  // namespace lifelong::slam
