#include "eval/metrics/trajectory_reference.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lifelong::eval {
namespace {

constexpr double kRadToDeg = 57.29577951308232;

Pose2 Interpolate(const StampedPose& a, const StampedPose& b, double t) {
  const double span = b.stamp_s - a.stamp_s;
  const double s = span > 0.0 ? (t - a.stamp_s) / span : 0.0;
  const Pose2& p = a.T_world_robot;
  const Pose2& q = b.T_world_robot;
  return Pose2(p.x + s * (q.x - p.x), p.y + s * (q.y - p.y),
               NormalizeAngle(p.theta + s * NormalizeAngle(q.theta - p.theta)));
}

}  // namespace

ReferencePairs PairWithReference(const std::vector<StampedPose>& estimate,
                                 const std::vector<StampedPose>& reference, double max_gap_s,
                                 double tolerance_s) {
  std::vector<StampedPose> ref = reference;
  std::stable_sort(ref.begin(), ref.end(), [](const StampedPose& a, const StampedPose& b) {
    return a.stamp_s < b.stamp_s;
  });
  ReferencePairs pairs;
  for (std::size_t k = 0; k < estimate.size(); ++k) {
    const StampedPose& e = estimate[k];
    const double t = e.stamp_s;
    const auto after = std::lower_bound(
        ref.begin(), ref.end(), t, [](const StampedPose& p, double s) { return p.stamp_s < s; });
    std::optional<Pose2> at;
    if (after != ref.end() && after->stamp_s - t <= tolerance_s) {
      at = after->T_world_robot;
    } else if (after != ref.begin() && t - std::prev(after)->stamp_s <= tolerance_s) {
      at = std::prev(after)->T_world_robot;
    } else if (after != ref.end() && after != ref.begin() &&
               after->stamp_s - std::prev(after)->stamp_s <= max_gap_s) {
      at = Interpolate(*std::prev(after), *after, t);
    }
    if (!at) {
      ++pairs.unmatched;
      continue;
    }
    pairs.estimate.push_back(e.T_world_robot);
    pairs.reference.push_back(*at);
    pairs.index.push_back(k);
  }
  return pairs;
}

ReferencePairs PairScanByScan(const std::vector<StampedPose>& estimate,
                              const std::vector<StampedPose>& reference) {
  if (estimate.size() != reference.size()) return PairWithReference(estimate, reference);
  ReferencePairs pairs;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    pairs.estimate.push_back(estimate[i].T_world_robot);
    pairs.reference.push_back(reference[i].T_world_robot);
    pairs.index.push_back(i);
  }
  return pairs;
}

DistanceRpe ComputeRpeAtDistance(const std::vector<Pose2>& estimate,
                                 const std::vector<Pose2>& reference, double distance_m) {
  if (estimate.size() != reference.size()) {
    throw std::invalid_argument("ComputeRpeAtDistance: sizes differ");
  }
  if (!(distance_m > 0.0)) throw std::invalid_argument("ComputeRpeAtDistance: distance <= 0");
  // along[k]: reference path length from pose 0 to pose k.
  std::vector<double> along(reference.size(), 0.0);
  for (std::size_t k = 1; k < reference.size(); ++k) {
    along[k] = along[k - 1] +
               std::hypot(reference[k].x - reference[k - 1].x, reference[k].y - reference[k - 1].y);
  }
  DistanceRpe r;
  double t_sq = 0.0, r_sq = 0.0;
  std::size_t j = 0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    j = std::max(j, i + 1);
    while (j < reference.size() && along[j] - along[i] < distance_m - kRpeDistanceTolerance_m) ++j;
    if (j >= reference.size()) break;
    const Pose2 err =
        Between(Between(reference[i], reference[j]), Between(estimate[i], estimate[j]));
    const double t = Norm(err), a = std::abs(err.theta) * kRadToDeg;
    t_sq += t * t;
    r_sq += a * a;
    ++r.count;
  }
  if (r.count > 0) {
    r.trans_rmse_m = std::sqrt(t_sq / static_cast<double>(r.count));
    r.rot_rmse_deg = std::sqrt(r_sq / static_cast<double>(r.count));
  }
  return r;
}

}  // namespace lifelong::eval
