#include "slam/matching/sequential_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>

#include "slam/matching/match_degeneracy.hpp"

namespace lifelong::slam {

Eigen::Matrix3d OdometryInformation(const IncrementalConfig& c, const Pose2& delta) {
  const double sxy = c.odom_sigma_xy_m + c.odom_sigma_xy_per_m * Norm(delta);
  const double sth = c.odom_sigma_rad + c.odom_sigma_rad_per_rad * std::abs(delta.theta);
  return Eigen::Vector3d(1.0 / (sxy * sxy), 1.0 / (sxy * sxy), 1.0 / (sth * sth)).asDiagonal();
}

Eigen::Matrix3d LostStepInformation(const IncrementalConfig& c) {
  const double w2 = c.lost_window_m * c.lost_window_m;
  const double t2 = kLostStepWindowRad * kLostStepWindowRad;
  return Eigen::Vector3d(1.0 / w2, 1.0 / w2, 1.0 / t2).asDiagonal();
}

SequentialMatch SequentialMatcher::Match(const NodeStore& nodes, const Values& values,
                                         const std::vector<NodeId>& recent, const Pose2& X_last,
                                         const Pose2& delta,
                                         const std::vector<Eigen::Vector2d>& points,
                                         bool odometry_lost) {
  const Pose2 guess = X_last * delta;
  SequentialMatch out;
  out.X_new = guess;
  out.lost = odometry_lost;
  // The odometry's information is the same in any frame; a lost step has almost none.
  const Eigen::Matrix3d odometry =
      odometry_lost ? LostStepInformation(config_) : OdometryInformation(config_, delta);
  out.information = odometry;
  MatcherConfig mc = config_.matcher;
  if (odometry_lost) {
    mc.linear_window_m = config_.lost_window_m;
    mc.angular_window_rad = kLostStepWindowRad;
  }
  MatchResult match = Search(points, guess, mc, LocalMap(nodes, values, recent));
  const bool refused = match.ok && WeakAndAmbiguous(match, config_);
  if ((!match.ok || refused) && !odometry_lost && config_.recovery_window_m > mc.linear_window_m) {
    MatcherConfig wide = mc;
    wide.linear_window_m = config_.recovery_window_m;
    // The local map again (its surfaces are cached): the first search cropped its copy, and
    // keeping one uncropped would cost every step a copy for the rare one that recovers.
    const MatchResult second = Search(points, guess, wide, LocalMap(nodes, values, recent));
    if (Recovers(second)) {
      match = second;
      out.recovered = true;
    }
  }
  if (!match.ok) return out;
  if (!out.recovered && refused) {
    out.weak = true;
    return out;
  }
  out.X_new = match.T_ref_cur;
  Eigen::Matrix3d information = match.information;  // in the world frame
  if (match.ambiguity > config_.max_ambiguity) {
    TakeDegenerateDirectionFromGuess(guess, odometry, match, &out.X_new, &information);
    out.degenerate = true;
  }
  out.information = RotateIntoFrame(information, out.X_new.theta);
  out.matched = true;
  return out;
}

MatchResult SequentialMatcher::Search(const std::vector<Eigen::Vector2d>& points,
                                      const Pose2& guess, const MatcherConfig& mc,
                                      std::vector<Eigen::Vector2d> reference) {
  CropToSearch(points, guess, mc, &reference);
  if (reference.size() < 10 || points.size() < 10) return {};
  grid_.Build(reference, mc);
  return ::lifelong::slam::Match(grid_, points, guess, mc);
}

bool SequentialMatcher::Recovers(const MatchResult& match) const {
  return match.ok && match.score >= config_.weak_score &&
         match.ambiguity <= config_.weak_max_ambiguity;
}

std::vector<Eigen::Vector2d> SequentialMatcher::LocalMap(const NodeStore& nodes,
                                                         const Values& values,
                                                         const std::vector<NodeId>& recent) {
  const auto count = static_cast<std::ptrdiff_t>(config_.local_map_nodes);
  const auto first = recent.end() - std::min(count, static_cast<std::ptrdiff_t>(recent.size()));
  std::map<NodeId, std::vector<Eigen::Vector2d>> kept;
  std::vector<Eigen::Vector2d> reference;
  for (auto it = first; it != recent.end(); ++it) {
    const NodeId id = *it;
    const std::vector<Eigen::Vector2d>* local = &nodes.at(id).points;
    if (config_.surfaces.JoinsAny()) {
      const auto cached = local_surfaces_.find(id);
      local = &(kept[id] = cached != local_surfaces_.end()
                               ? std::move(cached->second)
                               : ScanSurfaces(nodes.at(id).scan, config_, config_.surfaces));
    }
    const auto world = ToWorld(*local, values.at(id));
    reference.insert(reference.end(), world.begin(), world.end());
  }
  local_surfaces_ = std::move(kept);
  return reference;
}

}  // namespace lifelong::slam
